// Acne classed by its cause on rendered scenes (docs/metrics.md; issue 45): the shadow-map family
// says per pixel what its own depth comparison saw (docs/exr-channels.md), so a screen-space blur
// that carries the floor's shadow across a depth edge onto the occluder is screen-space bleed, and
// a surface that shadows itself at zero bias stays acne. Label "gl".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "core/lights/make_light.h"
#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

// The raster image without the depth comparison's channels: what the geometric rule sees, as for
// an external image.
ChannelImage withoutDepthChannels(const ChannelImage& image) {
    ChannelImage out(image.width(), image.height());
    for (const std::string& name : image.names()) {
        const std::string suffix = name.substr(name.rfind('.') + 1);
        if (suffix == ch::kMapDepth || suffix == ch::kReceiverDepth || suffix == ch::kMapTexel ||
            suffix == ch::kVisibilityUnfiltered)
            continue;
        std::copy_n(image.channel(name), image.pixelCount(), out.addChannel(name));
    }
    return out;
}

size_t marked(const ErrorMaps& maps, Artifact a, const ChannelImage& image, float mesh) {
    const float* M = image.channel(ch::kMeshId);
    size_t n = 0;
    for (size_t i = 0; i < maps.of(a).size(); ++i) n += maps.of(a)[i] != 0.0f && M[i] == mesh;
    return n;
}

// The scene shape: a flat square occluder (mesh 1) over a floor (mesh 0) under a rect
// light, seen from above at an angle. blur:radius=8 darkens the occluder's top face, fully lit in
// the oracle, next to the floor's penumbra: the geometric rule calls that acne. The hard shadow's
// own comparison lit those pixels: the blur carried the floor's shadow over, screen-space bleed,
// all of it on the occluder. The bilateral blur, which stops at the depth edge, bleeds less.
TEST(AcneCause, BlurAcrossADepthEdgeIsScreenBleedNotAcne) {
    REQUIRE_GL();
    const Scene s = makePenumbraScene(96, 72).scene;
    const ChannelImage o = runQuiet(s);
    const ChannelImage r = renderOneFrame(s, "blur", {"radius=8"}, false).image;
    ASSERT_TRUE(r.has(ch::lightChannel("panel", ch::kVisibilityUnfiltered)));
    ErrorMaps maps;
    const LightMetrics byCause = computeLightMetrics(o, r, "panel", {}, &maps);
    const LightMetrics geometric = computeLightMetrics(o, withoutDepthChannels(r), "panel", {});
    const ChannelImage bilateral =
        renderOneFrame(s, "blur", {"radius=8", "bilateral=on"}, false).image;
    const LightMetrics bilateralByCause = computeLightMetrics(o, bilateral, "panel", {});
    ASSERT_TRUE(byCause.screenBleedRate && bilateralByCause.screenBleedRate);
    const size_t bleedOnOccluder = marked(maps, Artifact::ScreenBleed, r, 1.0f),
                 bleedOnFloor = marked(maps, Artifact::ScreenBleed, r, 0.0f);
    std::printf(
        "[ acne cause ] blur:radius=8: acne_rate geometric %.4f, by cause %.4f; "
        "screen_bleed_rate %.4f (%zu pixels on the occluder, %zu on the floor); bilateral %.4f\n",
        geometric.acneRate, byCause.acneRate, *byCause.screenBleedRate, bleedOnOccluder,
        bleedOnFloor, *bilateralByCause.screenBleedRate);
    EXPECT_GT(geometric.acneRate, 0.01);  // the finding
    EXPECT_EQ(byCause.acneRate, 0.0);
    EXPECT_GT(bleedOnOccluder, 20u);
    EXPECT_EQ(bleedOnFloor, 0u);
    EXPECT_DOUBLE_EQ(*byCause.screenBleedRate, double(bleedOnOccluder) / double(byCause.counted));
    EXPECT_LT(*bilateralByCause.screenBleedRate, 0.5 * *byCause.screenBleedRate);
}

// A plane lit at a grazing angle (12 degrees) with no bias: basic shadows it with its own depth,
// acne by its cause as by the geometric rule; slope-bias cures it by either count.
TEST(AcneCause, ZeroBiasOnAGrazingPlaneIsAcne) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {20, 0, 0}, {0, 0, -20}, 8, "plane"));
    const double el = 12.0 * std::numbers::pi / 180.0;
    s.lights = {
        directionalLight("sun", glm::normalize(glm::dvec3(-std::cos(el), -std::sin(el), -0.2)))};
    aimCamera(s, {0, 12, 14}, {0, 0, 0}, 45, 96, 72);
    finalizeScene(s);
    const ChannelImage o = runQuiet(s);
    const ChannelImage basic = renderOneFrame(s, "basic", {"resolution=1024"}, false).image;
    const ChannelImage slope = renderOneFrame(s, "slope-bias", {"resolution=1024"}, false).image;
    ErrorMaps maps;
    const LightMetrics byCause = computeLightMetrics(o, basic, "sun", {}, &maps);
    const LightMetrics geometric = computeLightMetrics(o, withoutDepthChannels(basic), "sun", {});
    const LightMetrics slopeByCause = computeLightMetrics(o, slope, "sun", {});
    std::printf(
        "[ acne cause ] grazing plane: basic acne_rate geometric %.4f, by cause %.4f; "
        "slope-bias by cause %.5f\n",
        geometric.acneRate, byCause.acneRate, slopeByCause.acneRate);
    EXPECT_GT(byCause.acneRate, 0.05);
    EXPECT_EQ(byCause.acneRate, geometric.acneRate);
    EXPECT_FALSE(byCause.screenBleedRate);  // no screen-space pass: V is the comparison's own
    EXPECT_EQ(marked(maps, Artifact::OtherFalseShadow, basic, 0.0f), 0u);
    EXPECT_LT(slopeByCause.acneRate, 0.005);
}

// The channels exist where a depth map is compared (basic, pcf, blur's hard shadow), with
// V_unfiltered only after a screen-space pass (blur), and not for moment maps (vsm); a counted
// frame before them (work counts on) leaves them there. Where the camera sees nothing, nothing
// was compared (-1); on lit pixels the receiver's depth lies within the margin of the map's.
TEST(AcneCause, DepthChannelsWhereADepthMapIsCompared) {
    REQUIRE_GL();
    const Scene s = makePenumbraScene(48, 36).scene;
    const auto has = [](const ChannelImage& image, const char* suffix) {
        return image.has(ch::lightChannel("panel", suffix));
    };
    for (const auto& [technique, depth, unfiltered] :
         {std::tuple{"basic", true, false}, std::tuple{"pcf", true, false},
          std::tuple{"blur", true, true}, std::tuple{"vsm", false, false}}) {
        const ChannelImage r = renderOneFrame(s, technique, {"resolution=256"}, true).image;
        EXPECT_EQ(has(r, ch::kMapDepth), depth) << technique;
        EXPECT_EQ(has(r, ch::kReceiverDepth), depth) << technique;
        EXPECT_EQ(has(r, ch::kMapTexel), depth) << technique;
        EXPECT_EQ(has(r, ch::kVisibilityUnfiltered), unfiltered) << technique;
        if (!depth) continue;
        const float *A = r.channel(ch::kHit), *V = r.channel(ch::lightChannel("panel", "V")),
                    *MD = r.channel(ch::lightChannel("panel", ch::kMapDepth)),
                    *RD = r.channel(ch::lightChannel("panel", ch::kReceiverDepth)),
                    *MT = r.channel(ch::lightChannel("panel", ch::kMapTexel));
        size_t background = 0, nothingCompared = 0, lit = 0;
        for (size_t i = 0; i < r.pixelCount(); ++i) {
            if (A[i] == 0.0f) {
                ++background;
                nothingCompared += MD[i] == -1.0f && RD[i] == -1.0f && MT[i] == 0.0f;
                continue;
            }
            // The floor faces the light head on here (n.l near 1): the margin is about 2 texels.
            if (V[i] == 1.0f && RD[i] > 0.0f) lit += std::fabs(RD[i] - MD[i]) <= 2.0f * MT[i];
        }
        EXPECT_EQ(nothingCompared, background) << technique;
        EXPECT_GT(lit, r.pixelCount() / 4) << technique;
    }
}

}  // namespace
}  // namespace so::test
