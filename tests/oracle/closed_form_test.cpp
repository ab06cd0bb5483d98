// The hard-shadow oracle against answers computed in double, independently of Embree.
#include <cmath>
#include <cstring>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "core/lights/light_kind.h"
#include "core/lights/make_light.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

// The exact answer for one pixel of the square-occluder scene. `margin` gets the distance (in
// world units) from where the segment crosses the occluder's plane to the nearest edge line, or
// from the spot cone's boundary, so ambiguous pixels can be left out.
struct Exact {
    bool visible = true;
    double margin = INFINITY;
};

Exact exactSquare(const glm::dvec3& p, const Light& light) {
    using S = SquareOccluderScene;
    Exact e;
    glm::dvec3 toLight = isDirectional(light) ? -light.wsDirection : light.wsPosition - p;
    if (hasCone(light)) {
        double c = glm::dot(glm::normalize(p - light.wsPosition), light.wsDirection);
        double cosOuter = std::cos(light.outerConeDeg * std::numbers::pi / 180.0);
        e.margin = std::fabs(c - cosOuter) * glm::length(p - light.wsPosition);
        if (c < cosOuter) {
            e.visible = false;
            return e;
        }
    }
    // The segment p + t * toLight, t in (0, 1] (directional: t > 0) crosses y = h once at most.
    if (toLight.y == 0.0) return e;
    double t = (S::kOccluderY - p.y) / toLight.y;
    bool withinSegment = t > 1e-12 && (isDirectional(light) || t < 1.0);
    if (!withinSegment) return e;
    glm::dvec3 q = p + t * toLight;
    e.margin = std::min({e.margin, std::fabs(q.x - S::kX0), std::fabs(q.x - S::kX1),
                         std::fabs(q.z - S::kZ0), std::fabs(q.z - S::kZ1)});
    e.visible = !(q.x > S::kX0 && q.x < S::kX1 && q.z > S::kZ0 && q.z < S::kZ1);
    return e;
}

glm::dvec3 pixelPoint(const ChannelImage& img, size_t i) {
    return {img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]};
}

TEST(ClosedForm, SquareOccluderMatchesExactSegmentTest) {
    SquareOccluderScene s = makeSquareOccluderScene(192, 160);
    ChannelImage img = runQuiet(s.scene);
    const double sceneSize = s.scene.wsBounds.extent();
    const float* A = img.channel(ch::kHit);
    for (const Light& light : s.scene.lights) {
        const float* V = img.channel(ch::lightChannel(light.name, ch::kVisibility));
        size_t checked = 0, excluded = 0, shadowed = 0, lit = 0, wrong = 0;
        for (size_t i = 0; i < img.pixelCount(); ++i) {
            if (A[i] == 0.0f) continue;
            Exact e = exactSquare(pixelPoint(img, i), light);
            if (e.margin < 1e-6 * sceneSize) {
                ++excluded;
                continue;
            }
            ++checked;
            (e.visible ? lit : shadowed) += 1;
            if (V[i] != (e.visible ? 1.0f : 0.0f)) {
                if (++wrong <= 5)
                    ADD_FAILURE() << light.name << ": pixel " << i % size_t(img.width()) << ","
                                  << i / size_t(img.width()) << " V=" << V[i] << " exact "
                                  << e.visible << " margin " << e.margin;
            }
        }
        EXPECT_EQ(wrong, 0u) << light.name;
        // The scene must exercise both answers, or the comparison proves nothing.
        EXPECT_GT(shadowed, 500u) << light.name;
        EXPECT_GT(lit, 5000u) << light.name;
        EXPECT_LT(excluded, checked / 100) << light.name;
        std::printf(
            "[ closed form ] %s: %zu pixels checked (%zu lit, %zu shadowed), %zu excluded near "
            "edges\n",
            light.name.c_str(), checked, lit, shadowed, excluded);
    }
}

TEST(ClosedForm, VisibilityIsExactlyZeroOrOne) {
    SquareOccluderScene s = makeSquareOccluderScene(64, 64);
    ChannelImage img = runQuiet(s.scene);
    for (const Light& light : s.scene.lights) {
        const float* V = img.channel(ch::lightChannel(light.name, ch::kVisibility));
        for (size_t i = 0; i < img.pixelCount(); ++i) ASSERT_TRUE(V[i] == 0.0f || V[i] == 1.0f);
    }
}

// An unoccluded plane lit ever closer to grazing: every pixel that faces the light must be lit.
TEST(Grazing, NoFalseShadowDownToCos1e5) {
    const glm::dvec3 normals[] = {glm::normalize(glm::dvec3(0.3, 1.0, 0.2)), glm::dvec3(0, 1, 0),
                                  glm::normalize(glm::dvec3(-0.7, 0.4, 0.9))};
    const glm::dvec3 offsets[] = {glm::dvec3(0.0), glm::dvec3(1000.25, -37.5, 512.0),
                                  glm::dvec3(1e5, 3e4, -7e4)};
    for (const glm::dvec3& n : normals) {
        glm::dvec3 t1 = glm::normalize(glm::cross(n, glm::dvec3(0.123, 0.456, 0.789)));
        glm::dvec3 t2 = glm::cross(n, t1);
        for (const glm::dvec3& origin : offsets) {
            Scene scene;
            scene.meshes.push_back(makeGrid(origin, 20.0 * t1, 20.0 * t2, 12, "plane"));
            scene.camera.wsEye = origin + 14.0 * n + 3.0 * t1;
            scene.camera.wsTarget = origin;
            scene.camera.wsUp = t2;
            scene.camera.width = scene.camera.height = 96;
            for (int k = 1; k <= 5; ++k) {
                double c = std::pow(10.0, -k);
                double s = std::sqrt(1.0 - c * c);
                for (int az = 0; az < 4; ++az) {
                    double phi = 0.4 + az * std::numbers::pi / 2;
                    glm::dvec3 toLight = c * n + s * (std::cos(phi) * t1 + std::sin(phi) * t2);
                    Light sun = directionalLight(
                        "sun_" + std::to_string(k) + "_" + std::to_string(az), -toLight);
                    scene.lights.push_back(sun);
                    // A point light far along the same direction grazes the same way.
                    Light pt = pointLight("pt_" + std::to_string(k) + "_" + std::to_string(az),
                                          origin + 1e3 * toLight);
                    scene.lights.push_back(pt);
                }
            }
            finalizeScene(scene);
            ChannelImage img = runQuiet(scene);
            const float* A = img.channel(ch::kHit);
            size_t hits = 0;
            for (size_t i = 0; i < img.pixelCount(); ++i) hits += A[i] != 0.0f;
            ASSERT_GT(hits, img.pixelCount() / 2);
            for (const Light& l : scene.lights) {
                const float* V = img.channel(ch::lightChannel(l.name, ch::kVisibility));
                const float* C = img.channel(ch::lightChannel(l.name, ch::kCosine));
                size_t falseShadow = 0, facing = 0;
                for (size_t i = 0; i < img.pixelCount(); ++i) {
                    if (A[i] == 0.0f || C[i] <= 0.0f) continue;
                    ++facing;
                    falseShadow += V[i] != 1.0f;
                }
                EXPECT_EQ(falseShadow, 0u) << l.name << " normal " << n.x << "," << n.y << ","
                                           << n.z << " origin " << origin.x;
                // Point lights 1000 away see the plane at slightly varying angles; the directional
                // light must see every hit pixel as facing it.
                if (isDirectional(l)) {
                    EXPECT_EQ(facing, hits) << l.name;
                }
            }
        }
    }
}

// Translating by 2^16 and scaling by 2^-10 or 2^10 must not change a single visibility bit.
TEST(Invariance, TranslateAndScaleGiveIdenticalVisibility) {
    SquareOccluderScene s = makeSquareOccluderScene(128, 128);
    ChannelImage ref = runQuiet(s.scene);
    struct Case {
        double scale;
        glm::dvec3 t;
    };
    const Case cases[] = {{1.0, {65536.0, 65536.0, -65536.0}},
                          {std::ldexp(1.0, -10), {0, 0, 0}},
                          {std::ldexp(1.0, 10), {0, 0, 0}},
                          {std::ldexp(1.0, 10), {65536.0, 0.0, 65536.0}}};
    for (const Case& c : cases) {
        ChannelImage img = runQuiet(transformScene(s.scene, c.scale, c.t));
        std::vector<std::string> names = {ch::kHit, ch::kMeshId, ch::kPrimId};
        for (const Light& l : s.scene.lights) {
            names.push_back(ch::lightChannel(l.name, ch::kVisibility));
            names.push_back(ch::lightChannel(l.name, ch::kCosine));
        }
        for (const std::string& name : names) {
            EXPECT_EQ(0, std::memcmp(ref.channel(name), img.channel(name),
                                     ref.pixelCount() * sizeof(float)))
                << name << " differs at scale " << c.scale << " translate " << c.t.x;
        }
    }
}

// Without recentring, the same translation would quantise the scene to float steps of 2^-7: the
// invariance test above is only meaningful if such a change is visible, so check that it is.
TEST(Invariance, FloatQuantisationWouldBeVisible) {
    SquareOccluderScene s = makeSquareOccluderScene(128, 128);
    ChannelImage ref = runQuiet(s.scene);
    // Move the occluder by 2^-8, half the float spacing at 2^16: the shadow must change.
    Scene moved = s.scene;
    for (glm::dvec3& p : moved.meshes[1].wsPositions) p.x += std::ldexp(1.0, -8);
    finalizeScene(moved);
    ChannelImage img = runQuiet(moved);
    const std::string v = ch::lightChannel("point", ch::kVisibility);
    EXPECT_NE(0, std::memcmp(ref.channel(v), img.channel(v), ref.pixelCount() * sizeof(float)));
}

// A box resting on a plane: the shadow must reach the contact line.
TEST(Contact, ShadowReachesTheBoxBase) {
    Scene scene;
    scene.meshes.push_back(makeGrid({0, 0, 0}, {24, 0, 0}, {0, 0, -24}, 16, "floor"));
    scene.meshes.push_back(makeBox({-1, 0, -1}, {1, 2, 1}, "box"));
    const glm::dvec3 lightPos(3.5, 4.0, 2.5);
    scene.lights.push_back(pointLight("key", lightPos));
    // Looking from the side away from the light, so the shadowed faces and their base are in view.
    scene.camera.wsEye = {-6.0, 3.5, -5.0};
    scene.camera.wsTarget = {-0.5, 0.5, -0.5};
    scene.camera.vfovDeg = 45;
    scene.camera.width = scene.camera.height = 256;
    finalizeScene(scene);
    ChannelImage img = runQuiet(scene);
    const float* A = img.channel(ch::kHit);
    const float* mesh = img.channel(ch::kMeshId);
    const float* V = img.channel(ch::lightChannel("key", ch::kVisibility));
    const int w = img.width(), h = img.height();

    auto exactOccluded = [&](const glm::dvec3& p, double& margin) {
        // Slab test of the open segment p -> light against the box, in double.
        glm::dvec3 d = lightPos - p;
        double t0 = 1e-12, t1 = 1.0;
        const glm::dvec3 lo(-1, 0, -1), hi(1, 2, 1);
        for (int k = 0; k < 3; ++k) {
            if (d[k] == 0.0) {
                if (p[k] < lo[k] || p[k] > hi[k]) return false;
                continue;
            }
            double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
            t0 = std::max(t0, std::min(a, b));
            t1 = std::min(t1, std::max(a, b));
        }
        margin = (t1 - t0) * glm::length(d);  // chord length inside the box
        return t0 < t1;
    };

    size_t contactPixels = 0, leaks = 0, wrong = 0, checked = 0;
    for (int y = 1; y < h - 1; ++y) {
        for (int x = 1; x < w - 1; ++x) {
            size_t i = size_t(y) * size_t(w) + size_t(x);
            if (A[i] == 0.0f || mesh[i] != 0.0f) continue;  // floor pixels only
            glm::dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]);
            double chord = 0.0;
            bool occluded = exactOccluded(p, chord);
            if (occluded && chord < 1e-6 * scene.wsBounds.extent()) continue;  // grazes an edge
            ++checked;
            wrong += V[i] != (occluded ? 0.0f : 1.0f);
            // Contact: a floor pixel whose neighbour is the box, with the exact answer "shadow".
            bool besideBox = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) besideBox |= mesh[i + size_t(dy * w + dx)] == 1.0f;
            if (besideBox && occluded) {
                ++contactPixels;
                leaks += V[i] != 0.0f;
            }
        }
    }
    EXPECT_EQ(leaks, 0u);
    EXPECT_EQ(wrong, 0u) << "of " << checked << " floor pixels";
    EXPECT_GT(contactPixels, 40u) << "the view must show the contact line on the shadow side";
    std::printf("[ contact ] %zu floor pixels checked, %zu on the contact line, %zu leaks\n",
                checked, contactPixels, leaks);
}

TEST(Determinism, SameImageAtAnyThreadCount) {
    SquareOccluderScene s = makeSquareOccluderScene(160, 120);
    s.scene.meshes.push_back(makeBox({2, 0, 2}, {3, 1.5, 2.5}, "box"));
    finalizeScene(s.scene);
    ChannelImage ref = runQuiet(s.scene, 1);
    for (int threads : {2, 3, 8}) {
        ChannelImage img = runQuiet(s.scene, threads);
        ASSERT_EQ(ref.names(), img.names());
        for (const std::string& name : ref.names())
            EXPECT_EQ(0, std::memcmp(ref.channel(name), img.channel(name),
                                     ref.pixelCount() * sizeof(float)))
                << name << " differs with " << threads << " threads";
    }
}

}  // namespace
}  // namespace so::test
