// ShadowHistory (raster_compare/gl/time/shadow_history.h) on frames made in memory, no GL: a plane
// facing the camera, its V painted per pixel. Closed forms: a still frame keeps a constant, a step
// decays geometrically, weight 0 is the current V, a camera moved by one pixel moves the history
// by one pixel, another mesh or another place is a disocclusion, and the clamp bounds a ghost.
// A mesh that moves (meshMotion not the identity) is left to the animation work's tests: scenes
// made in memory have no animation yet.
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/channels.h"
#include "raster_compare/gl/time/shadow_history.h"

namespace so {
namespace {

constexpr int kWidth = 16, kHeight = 12;
const char* kLight = "sun";

CameraDesc frontCamera(double wsX = 0.0) {
    CameraDesc c;
    c.wsEye = {wsX, 0.0, 5.0};
    c.wsTarget = {wsX, 0.0, 0.0};
    c.width = kWidth;
    c.height = kHeight;
    c.vfovDeg = 40.0;
    return c;
}

// The world size of one pixel on the plane z = wsZ seen by frontCamera (5 - wsZ away).
double footprintAt(double wsZ) {
    return 2.0 * (5.0 - wsZ) * std::tan(20.0 * std::numbers::pi / 180.0) / kHeight;
}

// A frame that sees the plane through (0, 0, wsZ) with normal wsNormal (z = wsZ by default)
// everywhere, mesh `mesh(x, y)`, V `v(x, y)`; where `hit` is false the pixel missed (A 0, V 0).
struct PlaneFrame {
    ChannelImage image{kWidth, kHeight};
    CameraDesc camera;
    PlaneFrame(
        const CameraDesc& cam, double wsZ, const std::function<float(int, int)>& v,
        const std::function<float(int, int)>& mesh = [](int, int) { return 0.0f; },
        const std::function<bool(int, int)>& hit = [](int, int) { return true; },
        const glm::dvec3& wsNormal = {0.0, 0.0, 1.0})
        : camera(cam) {
        float* a = image.addChannel(channels::kHit);
        float* p[3] = {image.addChannel(channels::kPX), image.addChannel(channels::kPY),
                       image.addChannel(channels::kPZ)};
        float* id = image.addChannel(channels::kMeshId, -1.0f);
        float* vis = image.addChannel(channels::lightChannel(kLight, channels::kVisibility));
        const Camera c(cam);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                if (!hit(x, y)) continue;
                const size_t i = size_t(y) * kWidth + size_t(x);
                const Ray3d ray = c.generateRay(x, y);
                const double t = glm::dot(wsNormal, glm::dvec3(0.0, 0.0, wsZ) - ray.origin) /
                                 glm::dot(wsNormal, ray.direction);
                const glm::dvec3 ws = ray.origin + ray.direction * t;
                for (int k = 0; k < 3; ++k) p[k][i] = float(ws[k]);
                a[i] = 1.0f;
                id[i] = mesh(x, y);
                vis[i] = v(x, y);
            }
    }
    HistoryFrame frame(double t) const { return {&image, camera, t}; }
};

Scene twoMeshScene() {
    Scene s;
    s.meshes.resize(2);
    return s;
}

std::function<float(int, int)> constant(float c) {
    return [c](int, int) { return c; };
}

float at(const std::vector<float>& v, int x, int y) {
    return v[size_t(y) * kWidth + size_t(x)];
}

TEST(ShadowHistory, TheFirstFrameIsItsOwnVAndAConstantStaysConstant) {
    const Scene scene = twoMeshScene();
    ShadowHistory history({0.9, true}, kLight);
    const PlaneFrame first(frontCamera(), 0.0, [](int x, int y) { return float(x + y) / 32.0f; });
    const std::vector<float> r0 = history.resolve(scene, first.frame(0.0));
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) EXPECT_EQ(at(r0, x, y), float(x + y) / 32.0f);
    ShadowHistory still({0.9, false}, kLight);
    const PlaneFrame c(frontCamera(), 0.0, constant(0.37f));
    for (int frame = 0; frame < 4; ++frame)
        for (float r : still.resolve(scene, c.frame(frame / 30.0))) EXPECT_FLOAT_EQ(r, 0.37f);
}

TEST(ShadowHistory, AStepDecaysGeometricallyWithoutClamp) {
    const Scene scene = twoMeshScene();
    for (double w : {0.5, 0.9}) {
        ShadowHistory history({w, false}, kLight);
        const float a = 0.2f, b = 0.9f;
        history.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(a)).frame(0.0));
        const PlaneFrame after(frontCamera(), 0.0, constant(b));
        for (int k = 1; k <= 6; ++k) {
            const double wk = std::pow(w, k);
            const double expected = wk * a + (1.0 - wk) * b;
            for (float r : history.resolve(scene, after.frame(k / 30.0)))
                ASSERT_NEAR(r, expected, 1e-6) << "w " << w << ", frame " << k;
        }
    }
}

TEST(ShadowHistory, WeightZeroIsTheCurrentFrame) {
    const Scene scene = twoMeshScene();
    ShadowHistory history({0.0, true}, kLight);
    history.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(1.0f)).frame(0.0));
    const auto v = [](int x, int y) { return float((x * 7 + y * 3) % 5) / 4.0f; };
    const std::vector<float> r = history.resolve(scene, PlaneFrame(frontCamera(), 0.0, v).frame(1));
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) EXPECT_EQ(at(r, x, y), v(x, y));
}

TEST(ShadowHistory, ACameraMovedOnePixelMovesTheHistoryOnePixel) {
    const Scene scene = twoMeshScene();
    const double w = 0.75;
    ShadowHistory history({w, false}, kLight);
    const auto v0 = [](int x, int y) { return float(x) / 16.0f + float(y % 3) / 64.0f; };
    history.resolve(scene, PlaneFrame(frontCamera(), 0.0, v0).frame(0.0));
    // The camera one pixel's footprint to the right (+x): what pixel x + 1 saw is at pixel x.
    const PlaneFrame moved(frontCamera(footprintAt(0.0)), 0.0, constant(0.0f));
    const std::vector<float> r = history.resolve(scene, moved.frame(1.0 / 30.0));
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x + 1 < kWidth; ++x)
            EXPECT_NEAR(at(r, x, y), w * v0(x + 1, y), 1e-5) << x << ", " << y;
        EXPECT_EQ(at(r, kWidth - 1, y), 0.0f) << "was off screen: the current V alone";
    }
}

TEST(ShadowHistory, AnotherMeshOrAnotherPlaceIsADisocclusion) {
    const Scene scene = twoMeshScene();
    const double w = 0.9;
    // The left half saw mesh 1 before, mesh 0 now: its history is not read.
    ShadowHistory history({w, false}, kLight);
    history.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(1.0f), [](int x, int) {
                               return x < kWidth / 2 ? 1.0f : 0.0f;
                           }).frame(0.0));
    std::vector<float> r =
        history.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(0.0f)).frame(1.0));
    for (int x = 0; x < kWidth; ++x) EXPECT_NEAR(at(r, x, 5), x < kWidth / 2 ? 0.0 : w, 1e-6) << x;
    // The same mesh a footprint further away (well outside the tolerance): a new surface.
    ShadowHistory far({w, false}, kLight);
    far.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(1.0f)).frame(0.0));
    r = far.resolve(scene,
                    PlaneFrame(frontCamera(), -2.0 * footprintAt(0.0), constant(0.0f)).frame(1));
    for (float v : r) EXPECT_EQ(v, 0.0f);
    // A tenth of a footprint away: the same surface (float rounding, a slow motion).
    ShadowHistory near({w, false}, kLight);
    near.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(1.0f)).frame(0.0));
    r = near.resolve(scene,
                     PlaneFrame(frontCamera(), -0.1 * footprintAt(0.0), constant(0.0f)).frame(1));
    for (float v : r) EXPECT_NEAR(v, w, 1e-5);
}

// A plane turned 45 degrees about x, seen at 25 to 67 degrees from its normal: a camera moved up
// by 0.45 of a pixel finds each point in a texel whose own point lies up to 0.45 / cos 67 degrees,
// about 1.2 footprints, away along the slope. Every pixel keeps its history (the oblique
// allowance); a flat tolerance of half a footprint would drop most of them.
TEST(ShadowHistory, AnObliqueSurfaceKeepsItsHistoryUnderASmallMotion) {
    const Scene scene = twoMeshScene();
    const double w = 0.9;
    const glm::dvec3 tilted = glm::normalize(glm::dvec3(0.0, 1.0, 1.0));
    const auto any = [](int, int) { return 0.0f; };
    const auto all = [](int, int) { return true; };
    ShadowHistory history({w, false}, kLight);
    history.resolve(scene,
                    PlaneFrame(frontCamera(), 0.0, constant(1.0f), any, all, tilted).frame(0));
    CameraDesc up = frontCamera();
    up.wsEye.y += 0.45 * footprintAt(0.0);
    up.wsTarget.y += 0.45 * footprintAt(0.0);
    const std::vector<float> r =
        history.resolve(scene, PlaneFrame(up, 0.0, constant(0.0f), any, all, tilted).frame(1));
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) EXPECT_NEAR(at(r, x, y), w, 1e-5) << x << ", " << y;
}

TEST(ShadowHistory, TheClampBoundsABrightHistoryOverADarkNeighbourhood) {
    const Scene scene = twoMeshScene();
    const double w = 0.9;
    const auto dark = [](int x, int y) { return x == 5 && y == 5 ? 0.6f : 0.2f; };
    for (bool clamp : {false, true}) {
        ShadowHistory history({w, clamp}, kLight);
        history.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(1.0f)).frame(0.0));
        const std::vector<float> r =
            history.resolve(scene, PlaneFrame(frontCamera(), 0.0, dark).frame(1.0));
        if (!clamp) {
            EXPECT_NEAR(at(r, 2, 2), w + (1.0 - w) * 0.2, 1e-6) << "the ghost without a clamp";
            continue;
        }
        EXPECT_NEAR(at(r, 2, 2), 0.2, 1e-6);  // every neighbour 0.2: the history is 0.2
        EXPECT_NEAR(at(r, 4, 4), w * 0.6 + (1.0 - w) * 0.2, 1e-6);  // (5, 5) is a neighbour
        EXPECT_NEAR(at(r, 5, 5), 0.6, 1e-6);
    }
}

TEST(ShadowHistory, TheClampIgnoresTheBackgroundAndMissedPixelsKeepTheirV) {
    const Scene scene = twoMeshScene();
    const auto hit = [](int x, int) { return x != 8; };
    ShadowHistory history({0.9, true}, kLight);
    history.resolve(scene, PlaneFrame(frontCamera(), 0.0, constant(0.0f)).frame(0.0));
    const std::vector<float> r = history.resolve(
        scene, PlaneFrame(frontCamera(), 0.0, constant(0.5f), constant(0.0f), hit).frame(1.0));
    for (int y = 0; y < kHeight; ++y) {
        // Beside the missed column (V 0 there) the range is the hits' alone: [0.5, 0.5].
        EXPECT_NEAR(at(r, 7, y), 0.5, 1e-6);
        EXPECT_NEAR(at(r, 9, y), 0.5, 1e-6);
        EXPECT_EQ(at(r, 8, y), 0.0f);
    }
}

}  // namespace
}  // namespace so
