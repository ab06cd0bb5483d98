// Polygon lights (scene_format 4; core/lights/polygon.cpp, oracle/lights/polygon.cpp): the sampler
// against Lambert's closed form, the exact pass against the rect it equals and against the sampled
// pass's intervals, --verify, the shipped scene and its round trip. Bad polygons are in
// tests/data/broken_scene (expected.tsv, scene_loader_test.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/lights/light_kind.h"
#include "core/scene_writer.h"
#include "core/sobol.h"
#include "lambert.h"
#include "oracle/area_light.h"
#include "oracle/oracle.h"
#include "test_scenes.h"

namespace so::test {
namespace {

using glm::dvec3;

// The light as a scene description's one light, loaded as any scene's.
Light loadLight(const nlohmann::json& light) {
    const nlohmann::json description = {{"lights", nlohmann::json::array({light})}};
    return sceneFromMemory(description.dump(), {}).lights.at(0);
}

Light polygonLight(const std::string& name, const std::vector<dvec3>& vertices) {
    nlohmann::json vs = nlohmann::json::array();
    for (const dvec3& v : vertices) vs.push_back(nlohmann::json::array({v.x, v.y, v.z}));
    return loadLight({{"name", name}, {"type", "polygon"}, {"vertices", vs}});
}

// A regular n-gon of radius r about c in the horizontal plane, emitting down.
std::vector<dvec3> regularPolygon(const dvec3& c, double r, int n) {
    std::vector<dvec3> v;
    for (int k = 0; k < n; ++k) {
        const double a = 2.0 * std::numbers::pi * k / n;
        v.push_back(c + dvec3(r * std::cos(a), 0.0, r * std::sin(a)));
    }
    return v;
}

// int G dA over the light from p by the oracle's sampler: RQMC mean of the weights times the area
// (the pdf is 1 / area; the weights drop no other factor for a one-sided light).
double sampledIrradiance(const Light& light, const dvec3& p, const dvec3& n, uint32_t samples) {
    const AreaLight al = makeAreaLight(light, LocalFrame{});
    const AreaPixel px = prepareAreaPixel(al, glm::vec3(p), glm::vec3(n));
    double sum = 0.0;
    for (uint32_t first = 0; first < samples; first += 16) {
        float su[16], sv[16];
        sobol2DBlock(first, 16, 0x1234u, su, sv);
        AreaBatch b;
        mapAreaBatch(al, px, su, sv, 16, b);
        for (int k = 0; k < 16; ++k) sum += b.weight[k];
    }
    double twiceArea = 0.0;
    const std::vector<dvec3>& v = light.wsVertices;
    for (size_t k = 1; k + 1 < v.size(); ++k)
        twiceArea += glm::length(glm::cross(v[k] - v[0], v[k + 1] - v[0]));
    return sum / samples * 0.5 * twiceArea;
}

// The sampler's pdf is uniform by area over the fan: its estimate of int G dA converges to
// Lambert's formula for the polygon (tests/support/lambert.h, written independently), for a
// hexagon, a tilted triangle and a 40-gon, from receivers facing the light and tilted so that the
// horizon cuts it (those samples below it weigh 0).
TEST(PolygonLight, SamplerMatchesLambertsFormula) {
    const Light hexagon = polygonLight("hex", regularPolygon({0, 4, 0}, 1.2, 6));
    const Light triangle =
        polygonLight("tri", {{2.5, 3.0, -1.0}, {3.5, 2.6, -1.0}, {3.0, 3.2, 0.0}});
    const Light many = polygonLight("many", regularPolygon({0.3, 2, 0.1}, 0.8, 40));
    const dvec3 up(0, 1, 0), tilted = glm::normalize(dvec3(0.9, 0.25, 0.0));
    int checked = 0;
    for (const Light* l : {&hexagon, &triangle, &many})
        for (const dvec3& p : {dvec3(0, 0, 0), dvec3(1.5, 0, -0.5), dvec3(-0.2, 1.6, 0.3)})
            for (const dvec3& n : {up, tilted}) {
                const double reference = polygonIrradiance(p, n, l->wsVertices, l->wsEmitNormal());
                if (!(reference > 1e-3)) continue;
                const double sampled = sampledIrradiance(*l, p, n, 1u << 14);
                EXPECT_NEAR(sampled, reference, 2e-3 * reference)
                    << l->name << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
                ++checked;
            }
    EXPECT_GE(checked, 14);
}

// The closed-form scene with its rect light given as the polygon of its four corners: the exact
// pass gives the same V on every pixel (the corners and the frame are the rect's, bit for bit).
TEST(PolygonLight, FourGonEqualsTheRectExactly) {
    const PenumbraScene s = makePenumbraScene(96, 72);
    Scene poly = s.scene;
    const Light& rect = s.scene.lights[0];
    const dvec3 c = rect.wsPosition - 0.5 * rect.wsU - 0.5 * rect.wsV;
    poly.lights[0] =
        polygonLight("panel", {c, c + rect.wsU, c + rect.wsU + rect.wsV, c + rect.wsV});
    OracleOptions o;
    o.penumbra.method = PenumbraMethod::Exact;
    const OracleResult a = runOracle(s.scene, o), b = runOracle(poly, o);
    const float* Va = a.image.channel("panel.V");
    const float* Vb = b.image.channel("panel.V");
    size_t penumbra = 0, differ = 0;
    for (size_t i = 0; i < a.image.pixelCount(); ++i) {
        penumbra += Va[i] > 0.0f && Va[i] < 1.0f;
        differ += Va[i] != Vb[i];
    }
    EXPECT_GT(penumbra, 500u);
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(b.stats.lights[0].area->exact->errorKind, "exact");
}

// The shipped scene (a hexagonal softbox and a tilted triangle) and the closed-form scene under a
// 40-gon (beyond the pyramid's fixed buffers: integrated as a region of its bounding rectangle):
// the exact V lies within the sampled pass's 95% intervals at about the nominal rate.
TEST(PolygonLight, ExactWithinTheSampledIntervals) {
    Scene shipped = loadScene(std::string(SO_SCENES_DIR) + "/polygon_softbox.scene.json");
    PenumbraScene many = makePenumbraScene(96, 72);
    many.scene.lights[0] = polygonLight("panel", regularPolygon({0.5, 4, 0.25}, 1.0, 40));
    for (const Scene* scene : {&shipped, &many.scene}) {
        OracleOptions o;
        o.width = 96;
        o.height = 72;
        o.area.fixedSpp = 1024;
        o.penumbra.method = PenumbraMethod::Both;
        const OracleResult r = runOracle(*scene, o);
        for (const OracleLightStats& l : r.stats.lights) {
            const ExactPenumbraStats& st = *l.area->exact;
            const double n = double(st.pixelsExact), share = double(st.outsideInterval) / n;
            std::printf("[ polygon ] %s: %llu exact pixels, %.4f outside the 95%% interval\n",
                        l.name.c_str(), (unsigned long long)st.pixelsExact, share);
            EXPECT_GT(st.pixelsExact, 100u) << l.name;
            EXPECT_LE(share, 0.05 + 3.0 * std::sqrt(0.05 * 0.95 / n)) << l.name;
        }
    }
}

// --verify on polygon lights: the independent re-trace (uniform by area over the fan in double,
// reference_light.h) agrees with the exact pass's pixels.
TEST(PolygonLight, VerifyChecksTheExactPass) {
    Scene shipped = loadScene(std::string(SO_SCENES_DIR) + "/polygon_softbox.scene.json");
    OracleOptions o;
    o.width = 64;
    o.height = 48;
    o.penumbra.method = PenumbraMethod::Exact;
    o.verify.pixels = 100;
    const OracleResult r = runOracle(shipped, o);
    ASSERT_TRUE(r.stats.verify.has_value());
    ASSERT_EQ(r.stats.verify->lights.size(), 2u);
    for (const LightVerification& l : r.stats.verify->lights) {
        EXPECT_EQ(l.disagree, 0u) << l.light;
        EXPECT_GT(l.agree, l.checked * 9 / 10) << l.light;
    }
}

// The shipped scene loads as written, and the scene writer gives it back.
TEST(PolygonLight, ShippedSceneLoadsAndRoundTrips) {
    const Scene s = loadScene(std::string(SO_SCENES_DIR) + "/polygon_softbox.scene.json");
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& hex = s.lights[0];
    EXPECT_STREQ(lightTypeName(hex.type), "polygon");
    EXPECT_EQ(hex.wsVertices.size(), 6u);
    EXPECT_NEAR(glm::length(hex.wsEmitNormal() - dvec3(0, -1, 0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(hex.wsPosition - dvec3(0, 4, 0)), 0.0, 1e-12);  // area centroid
    EXPECT_TRUE(isAreaLight(hex));
    for (const Light& l : s.lights) {
        const Light back = loadLight(sceneLightJson(l));
        EXPECT_EQ(back.wsVertices, l.wsVertices);
        EXPECT_EQ(back.wsPosition, l.wsPosition);
        EXPECT_EQ(back.wsNormal, l.wsNormal);
    }
}

}  // namespace
}  // namespace so::test
