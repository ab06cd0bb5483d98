// smrt, shadow-map ray tracing (Unreal 5's SMRT, issue 54), on the plain map and on the adaptive
// (virtual) one. On the closed-form penumbra scene (a rect light over a parallel square occluder)
// its rays toward points on the light give a penumbra that the hard slope-bias has not, close to
// pcss's, which Fernando derived for exactly these parallel planes; with map=adaptive the rect
// light falls back to map=plain on a cube map of the pool's memory. Under a low sun the rays are
// marched through the virtual map's pages. Label "gl" (the parameter checks need no GL).
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "core/error.h"
#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "test_scenes.h"

namespace so::test {
namespace {

const RasterLightStats& lightStats(const RasterResult& r, const std::string& light) {
    for (const RasterLightStats& l : r.stats.lights)
        if (l.name == light) return l;
    throw std::runtime_error("no light " + light);
}

// The penumbra metrics of the panel light against the oracle, printed.
LightMetrics penumbraMetrics(const Scene& s, const ChannelImage& oracle, const std::string& t,
                             const std::vector<std::string>& settings = {}) {
    const RasterResult r = renderOneFrame(s, t, settings, false);
    const LightMetrics m = computeLightMetrics(oracle, r.image, "panel", {});
    std::string label = t;
    for (size_t i = 0; i < settings.size(); ++i) label += (i ? "," : ":") + settings[i];
    EXPECT_TRUE(m.penumbraMae && m.penumbraWidth) << label;
    std::printf("[ smrt ] %-40s penumbra_mae %.4f penumbra width error %.2f px (oracle %.2f)\n",
                label.c_str(), m.penumbraMae.value_or(-1),
                m.penumbraWidth ? m.penumbraWidth->mean : -1.0,
                m.penumbraWidth ? m.penumbraWidth->oracleMeanWidth : -1.0);
    return m;
}

// At two sizes, the rays not cut by an angle (max_ray_angle=1.5: Unreal's 0.03 keeps this light's
// penumbra to a sliver, raster_smrt_rays_test.cpp). With 7 rays on light points jittered per
// pixel (issue 63) each pixel's V is a 7-ray estimate, so its penumbra_mae holds the estimate's
// noise (0.089 here, 1.55 times pcss's) and only beats the hard shadow; with 64 rays the noise
// is small and what is left is the trace's own error: close to pcss's, which Fernando derived for
// exactly these parallel planes. (Before smrt's crossing test of issue 54, with one set of points
// for every pixel, it was 1.46 times pcss at 128 x 96 and 1.51 at 160 x 120.)
TEST(Smrt, PenumbraOfARectLightOverAParallelOccluder) {
    REQUIRE_GL();
    for (const auto& [width, height] : {std::pair{128, 96}, std::pair{160, 120}}) {
        SCOPED_TRACE(std::to_string(width) + " x " + std::to_string(height));
        const Scene s = makePenumbraScene(width, height).scene;
        const ChannelImage o = runQuiet(s);
        const LightMetrics smrt = penumbraMetrics(s, o, "smrt", {"max_ray_angle=1.5"}),
                           many = penumbraMetrics(s, o, "smrt", {"max_ray_angle=1.5", "rays=64"}),
                           adaptive = penumbraMetrics(
                               s, o, "smrt", {"max_ray_angle=1.5", "rays=64", "map=adaptive"}),
                           hard = penumbraMetrics(s, o, "slope-bias"),
                           pcss = penumbraMetrics(s, o, "pcss");
        ASSERT_TRUE(hard.penumbraMae && pcss.penumbraMae && hard.penumbraWidth);
        for (const LightMetrics* m : {&smrt, &many, &adaptive}) {
            ASSERT_TRUE(m->penumbraMae && m->penumbraWidth);
            EXPECT_LT(*m->penumbraMae, 0.5 * *hard.penumbraMae);
            EXPECT_LT(m->penumbraWidth->mean, 0.5 * hard.penumbraWidth->mean);
        }
        for (const LightMetrics* m : {&many, &adaptive})
            EXPECT_LE(*m->penumbraMae, 1.5 * *pcss.penumbraMae)
                << (m == &many ? "plain" : "adaptive");
    }
}

// A rect light has no virtual map: map=adaptive is smrt on a cube map of the pool's memory.
TEST(Smrt, AdaptiveMapFallsBackToAPlainCubeMapForAreaLights) {
    REQUIRE_GL();
    const Scene s = makePenumbraScene(64, 48).scene;
    const RasterResult a =
        renderOneFrame(s, "smrt", {"map=adaptive", "pool_mb=6", "rays=5"}, false);
    const RasterLightStats& st = lightStats(a, "panel");
    EXPECT_EQ(st.counts.at("cube_fallback"), 1);
    EXPECT_EQ(st.counts.at("cube_resolution"), 512);  // sqrt(6 MiB / 24)
    EXPECT_EQ(st.map, "cube");
    const RasterResult b =
        renderOneFrame(s, "smrt", {"resolution=512", "depth_format=32", "rays=5"}, false);
    const std::string v = channels::lightChannel("panel", channels::kVisibility);
    EXPECT_TRUE(std::equal(a.image.channel(v), a.image.channel(v) + a.image.pixelCount(),
                           b.image.channel(v)));
}

// Under a low sun over a long ground the virtual map's pages follow the pixels' footprints: with
// the pool the same memory as the plain map, smrt's hard shadow is no worse through the pages.
TEST(Smrt, AdaptiveMapUnderASunIsNoWorseThanThePlainMapOfItsMemory) {
    REQUIRE_GL();
    const Scene s = makeGroundPostsScene(160, 120);
    const ChannelImage oracle = runQuiet(s);
    // 4 MiB: a pool of 256 pages of 128^2 32-bit texels, a plain map of 1024^2 32-bit texels.
    const RasterResult plain = renderOneFrame(s, "smrt", {"resolution=1024", "depth_format=32"});
    const RasterResult paged = renderOneFrame(s, "smrt", {"map=adaptive", "pool_mb=4"});
    const RasterLightStats& st = lightStats(paged, "sun");
    EXPECT_EQ(st.passes, (std::vector<std::string>{"mark", "pages", "refine", "visibility"}));
    EXPECT_EQ(st.counts.at("pool_pages") * 128 * 128, 1024 * 1024);
    const LightMetrics a = computeLightMetrics(oracle, paged.image, "sun", {}),
                       b = computeLightMetrics(oracle, plain.image, "sun", {});
    std::printf(
        "[ smrt ] sun, 4 MiB: map=adaptive mae %.4f p95 %.2f px (%lld pages); map=plain "
        "1024 mae %.4f p95 %.2f px\n",
        a.mae, a.boundaryDisplacement.p95, (long long)st.counts.at("pages_rendered"), b.mae,
        b.boundaryDisplacement.p95);
    EXPECT_GT(b.boundaryDisplacement.pixels, 100u) << "the scene has shadow edges to measure";
    EXPECT_LE(a.mae, b.mae);
    EXPECT_LE(a.boundaryDisplacement.p95, b.boundaryDisplacement.p95);
}

// Every page at level 0 (density far above need) and a pool that holds them all: each sample
// reads the texel the plain map of the virtual size holds, so V is the plain map's, but where a
// ray's samples leave the pages the receivers asked for and read a coarser level (the mark pass
// asks for receivers only), or the cropped projection's rounding moves a texel at a triangle edge.
TEST(Smrt, AdaptiveMapAtLevelZeroReproducesThePlainMap) {
    REQUIRE_GL();
    Scene s = makeSquareOccluderScene(160, 120).scene;
    s.lights = {s.lights[1], s.lights[2]};  // spot and sun (the point light has no virtual map)
    const RasterResult a = renderOneFrame(
        s, "smrt",
        {"map=adaptive", "virtual_size=1024", "page_size=128", "pool_mb=64", "density=1024"},
        false);
    const RasterResult b = renderOneFrame(s, "smrt", {"resolution=1024", "depth_format=32"}, false);
    for (const Light& l : s.lights) {
        EXPECT_EQ(lightStats(a, l.name).counts.at("pages_dropped"), 0) << l.name;
        const std::string v = channels::lightChannel(l.name, channels::kVisibility);
        const float *va = a.image.channel(v), *vb = b.image.channel(v);
        size_t differ = 0;
        for (size_t i = 0; i < a.image.pixelCount(); ++i) differ += va[i] != vb[i];
        std::printf("[ smrt ] level 0, %s: %zu of %zu pixels differ from map=plain\n",
                    l.name.c_str(), differ, a.image.pixelCount());
        EXPECT_LE(differ, a.image.pixelCount() / 2000) << l.name;
    }
}

// temporal=on over the pages: a sequence's frames render (a sun and a spot through the pages, a
// point light through the cube fallback), each frame index the same every time.
TEST(Smrt, AdaptiveMapWithTemporalRendersASequence) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(64, 48).scene;
    std::string why;
    auto frame = [&](int index) {
        RasterOptions o;
        o.frames = 2, o.warmup = 1, o.countWork = false, o.frameIndex = index;
        return renderRaster(s, *createTechnique("smrt", {"map=adaptive", "temporal=on"}), o,
                            *glContext(why));
    };
    for (int index = 0; index < 4; ++index) {
        const RasterResult r = frame(index);
        for (const Light& l : s.lights) {
            const float* v = r.image.channel(channels::lightChannel(l.name, channels::kVisibility));
            const size_t n = r.image.pixelCount();
            EXPECT_TRUE(std::all_of(v, v + n, [](float x) { return x >= 0.0f && x <= 1.0f; }));
            EXPECT_GT(std::count_if(v, v + n, [](float x) { return x < 0.5f; }), 0) << l.name;
        }
        EXPECT_EQ(lightStats(r, "point").counts.at("cube_fallback"), 1);
        EXPECT_EQ(lightStats(r, "sun").passes.front(), "mark");
        if (index == 3) {
            const std::string v = channels::lightChannel("spot", channels::kVisibility);
            const RasterResult again = frame(index);
            EXPECT_TRUE(std::equal(r.image.channel(v), r.image.channel(v) + r.image.pixelCount(),
                                   again.image.channel(v)));
        }
    }
}

TEST(Smrt, MapParametersNeedTheirMap) {
    for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
             {"pool_mb=4"},
             {"map=plain", "virtual_size=1024"},
             {"map=adaptive", "resolution=1024"},
             {"map=adaptive", "cascades=3"},
             {"map=adaptive", "contact=on"},
             {"map=adaptive", "depth_format=32"},
             {"map=adaptive", "virtual_size=256", "page_size=512"},
             {"map=adaptive", "page_size=1024", "pool_mb=3"},
             {"map=cube"}})
        EXPECT_THROW(createTechnique("smrt", bad), InputError) << bad.back();
    EXPECT_NO_THROW(createTechnique("smrt", {"map=adaptive", "pool_mb=4", "fit=receivers"}));
    EXPECT_NO_THROW(createTechnique("smrt", {"resolution=1024", "cascades=3", "contact=on"}));
}

}  // namespace
}  // namespace so::test
