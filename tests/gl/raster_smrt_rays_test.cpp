// smrt's rays as Unreal 5 ships them (issue 63): light points jittered per pixel, local lights'
// rays cut at max_ray_angle seen from the light (MaxRayAngleFromLight), the occluder's depth slope
// extrapolated behind it up to extrapolate_slope (ExtrapolateMaxSlope*, EEVEE-Next's hit check).
// On the closed-form penumbra scene (a rect light over a parallel square occluder), 160 x 120.
// Label "gl".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "core/error.h"
#include "gl_test_context.h"
#include "test_scenes.h"

namespace so::test {
namespace {

const std::string kPanelV = channels::lightChannel("panel", channels::kVisibility);

std::vector<float> panelV(const Scene& s, const std::vector<std::string>& settings) {
    const RasterResult r = renderOneFrame(s, "smrt", settings, false);
    const float* v = r.image.channel(kPanelV);
    return std::vector<float>(v, v + r.image.pixelCount());
}

size_t countDiffering(const std::vector<float>& a, const std::vector<float>& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
    return n;
}

struct Fixture {
    Scene scene = makePenumbraScene(160, 120).scene;
    ChannelImage oracle = runQuiet(scene);
    const float* oracleV() const { return oracle.channel(kPanelV); }
};

// The row with the most oracle penumbra pixels (0 < V < 1), and those pixels' columns.
std::vector<int> penumbraRow(const ChannelImage& oracle, int& row) {
    const float* o = oracle.channel(kPanelV);
    std::vector<int> best;
    for (int y = 0; y < oracle.height(); ++y) {
        std::vector<int> xs;
        for (int x = 0; x < oracle.width(); ++x) {
            const float v = o[size_t(y) * oracle.width() + x];
            if (v > 0.02f && v < 0.98f) xs.push_back(x);
        }
        if (xs.size() > best.size()) best = xs, row = y;
    }
    return best;
}

// A fixed set of light points for every pixel gives a staircase: across a straight penumbra V
// climbs through its 8 levels (7 rays), each level one run of pixels. Per-pixel points break it:
// neighbouring pixels see different points, so the levels interleave (53 runs of 6 levels here)
// while the row's mean still follows the oracle.
TEST(SmrtRays, PerPixelLightPointsBreakTheStaircase) {
    REQUIRE_GL();
    const Fixture f;
    int row = 0;
    const std::vector<int> xs = penumbraRow(f.oracle, row);
    ASSERT_GE(xs.size(), 12u) << "the scene has a penumbra row";
    const std::vector<float> v = panelV(f.scene, {"max_ray_angle=1.5"});
    std::set<float> levels;
    int runs = 0;
    double meanV = 0.0, meanOracle = 0.0;
    for (size_t k = 0; k < xs.size(); ++k) {
        const size_t i = size_t(row) * f.oracle.width() + xs[k];
        levels.insert(v[i]);
        runs += k == 0 || v[i] != v[i - (xs[k] - xs[k - 1])];
        meanV += v[i], meanOracle += f.oracleV()[i];
    }
    meanV /= double(xs.size()), meanOracle /= double(xs.size());
    std::printf(
        "[ smrt ] penumbra row %d: %zu pixels, %zu levels, %d runs, mean V %.3f (oracle "
        "%.3f)\n",
        row, xs.size(), levels.size(), runs, meanV, meanOracle);
    EXPECT_GE(levels.size(), 5u);
    EXPECT_GE(runs, 4 * int(levels.size()));  // fixed points: 9 runs of 5 levels here
    EXPECT_NEAR(meanV, meanOracle, 0.1);
}

// max_ray_angle=0 cuts every ray to the receiver itself: one depth test there, the slope-biased
// hard shadow, pixel for pixel. Unreal's 0.03 keeps this light's penumbra (rays up to 0.15 rad
// from its centre reach the occluder) to a sliver: fewer partial pixels than uncut rays give.
TEST(SmrtRayLimits, MaxRayAngleBoundsThePenumbra) {
    REQUIRE_GL();
    const Fixture f;
    const RasterResult hard = renderOneFrame(f.scene, "slope-bias", {}, false);
    const std::vector<float> zero = panelV(f.scene, {"max_ray_angle=0"});
    const float* h = hard.image.channel(kPanelV);
    EXPECT_EQ(countDiffering(zero, std::vector<float>(h, h + zero.size())), 0u);
    auto partial = [](const std::vector<float>& v) {
        return std::count_if(v.begin(), v.end(), [](float x) { return x > 0.0f && x < 1.0f; });
    };
    const long cut = partial(panelV(f.scene, {})),
               uncut = partial(panelV(f.scene, {"max_ray_angle=1.5"}));
    std::printf("[ smrt ] partial pixels: max_ray_angle 0.03 %ld, 1.5 %ld\n", cut, uncut);
    EXPECT_GT(cut, 0);
    EXPECT_LT(2 * cut, uncut);
}

// The slope is used only for a sample behind an occluder (in its shadow from the light's centre):
// with the occluder tilted 40 degrees (its depth slope seen from the light well above 0.05) V
// changes with extrapolate_slope near the shadow, and nowhere more than 3 pixels from a pixel the
// oracle shadows at all; the default for a rect light is Unreal's local 0.05.
TEST(SmrtRayLimits, ExtrapolateSlopeChangesOnlyRaysBehindOccluders) {
    REQUIRE_GL();
    Fixture f;
    const double tilt = 40.0 * 3.14159265358979 / 180.0;
    f.scene.meshes[1] = makeGrid({0, 1.5, 0}, {2, 0, 0},
                                 {0, 2 * std::sin(tilt), -2 * std::cos(tilt)}, 1, "occluder");
    finalizeScene(f.scene);
    f.oracle = runQuiet(f.scene);
    const std::vector<float> flat = panelV(f.scene, {"max_ray_angle=1.5", "extrapolate_slope=0"}),
                             steep =
                                 panelV(f.scene, {"max_ray_angle=1.5", "extrapolate_slope=1000"});
    const int w = f.oracle.width(), h = f.oracle.height();
    auto nearShadow = [&](int x, int y) {
        for (int dy = -3; dy <= 3; ++dy)
            for (int dx = -3; dx <= 3; ++dx) {
                const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
                if (f.oracleV()[size_t(yy) * w + xx] < 1.0f) return true;
            }
        return false;
    };
    size_t differ = 0, farFromShadow = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (flat[i] == steep[i]) continue;
            ++differ;
            farFromShadow += !nearShadow(x, y);
        }
    std::printf("[ smrt ] extrapolate_slope 0 vs 1000: %zu pixels differ, %zu far from shadow\n",
                differ, farFromShadow);
    EXPECT_GT(differ, 0u);
    EXPECT_EQ(farFromShadow, 0u);
    EXPECT_EQ(countDiffering(panelV(f.scene, {}), panelV(f.scene, {"extrapolate_slope=0.05"})), 0u);
}

// A sun's default is Unreal's directional 5.0, and max_ray_angle does not touch it.
TEST(SmrtRayLimits, ASunTakesTheDirectionalDefaultsAndNoAngle) {
    REQUIRE_GL();
    const Scene s = makeGroundPostsScene(96, 72);
    const std::string v = channels::lightChannel("sun", channels::kVisibility);
    auto sunV = [&](const std::vector<std::string>& settings) {
        const RasterResult r = renderOneFrame(s, "smrt", settings, false);
        const float* p = r.image.channel(v);
        return std::vector<float>(p, p + r.image.pixelCount());
    };
    const std::vector<float> byDefault = sunV({});
    EXPECT_EQ(countDiffering(byDefault, sunV({"extrapolate_slope=5"})), 0u);
    EXPECT_EQ(countDiffering(byDefault, sunV({"max_ray_angle=0"})), 0u);
}

TEST(SmrtRayLimits, ParametersAreChecked) {
    for (const char* bad : {"max_ray_angle=-0.1", "max_ray_angle=2", "extrapolate_slope=-2"})
        EXPECT_THROW(createTechnique("smrt", {bad}), InputError) << bad;
    EXPECT_NO_THROW(createTechnique("smrt", {"max_ray_angle=0", "extrapolate_slope=0"}));
}

}  // namespace
}  // namespace so::test
