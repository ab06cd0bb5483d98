// The adaptive (virtual) shadow map: its page bookkeeping on the CPU, and on GL its agreement with
// slope-bias where it must agree, its texel density following the camera, a full pool, its memory
// and its parameter checks (ctest label "gl"; the GL tests skip without EGL).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/lights/make_light.h"
#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/shadow_maps/virtual_shadow_map.h"
#include "raster_compare/gl/technique.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

TEST(AdaptivePages, LayoutStacksTheLevels) {
    const VirtualMapLayout layout{1024, 128};
    EXPECT_EQ(layout.levels(), 4);  // 8, 4, 2, 1 pages a side
    EXPECT_EQ(layout.tableWidth(), 8);
    EXPECT_EQ(layout.tableRow(1), 8);
    EXPECT_EQ(layout.tableRow(3), 14);
    EXPECT_EQ(layout.tableHeight(), 15);
    EXPECT_EQ((VirtualMapLayout{65536, 128}.levels()), 10);
}

TEST(AdaptivePages, AncestorsComeFirstAndThePoolCutsTheFinest) {
    const VirtualMapLayout layout{1024, 128};
    std::vector<uint32_t> pixels(size_t(layout.tableWidth() * layout.tableHeight()), 0);
    pixels[layout.cell(0, 3, 5)] = 7;  // one level-0 page: it and its 3 ancestors
    PageAllocation all = allocatePages(layout, pixels, 100);
    EXPECT_EQ(all.marked, 1);
    EXPECT_EQ(all.requested, 4);
    EXPECT_EQ(all.dropped, 0);
    ASSERT_EQ(all.pages.size(), 4u);
    EXPECT_EQ(all.pages[0].level, 3);  // the coarsest first
    EXPECT_EQ(all.finestLevel, 0);
    EXPECT_EQ(all.table[layout.cell(0, 3, 5)], 3);
    EXPECT_EQ(all.table[layout.cell(1, 1, 2)], 2);
    EXPECT_EQ(all.table[layout.cell(0, 3, 4)], -1);
    PageAllocation cut = allocatePages(layout, pixels, 2);
    EXPECT_EQ(cut.requested, 4);
    EXPECT_EQ(cut.dropped, 2);
    EXPECT_EQ(cut.finestLevel, 2);
    EXPECT_EQ(cut.table[layout.cell(0, 3, 5)], -1);
    EXPECT_EQ(cut.table[layout.cell(2, 0, 1)], 1);
    // No pixel at all: the coarsest page is still resident.
    PageAllocation none = allocatePages(layout, std::vector<uint32_t>(pixels.size(), 0), 1);
    EXPECT_EQ(none.requested, 1);
    ASSERT_EQ(none.pages.size(), 1u);
    EXPECT_EQ(none.table[layout.cell(3, 0, 0)], 0);
}

TEST(AdaptivePages, WithinALevelMostPixelsWin) {
    const VirtualMapLayout layout{1024, 128};
    std::vector<uint32_t> pixels(size_t(layout.tableWidth() * layout.tableHeight()), 0);
    pixels[layout.cell(1, 0, 0)] = 5;
    pixels[layout.cell(1, 3, 3)] = 50;
    pixels[layout.cell(1, 3, 0)] = 9;
    // 1 (level 3) + 3 (level 2: cells (0,0), (1,1), (1,0)) + 1 of the 3 level-1 pages.
    PageAllocation a = allocatePages(layout, pixels, 5);
    EXPECT_EQ(a.requested, 1 + 3 + 3);
    EXPECT_EQ(a.dropped, 2);
    EXPECT_GE(a.table[layout.cell(1, 3, 3)], 0);
    EXPECT_EQ(a.table[layout.cell(1, 0, 0)], -1);
    EXPECT_EQ(a.table[layout.cell(1, 3, 0)], -1);
}

// The pool goes first where pixels are served the most levels coarser than they need, even when
// fewer pixels are there: it evens out the aliasing rather than perfecting the crowded pages.
TEST(AdaptivePages, TheLargestDeficitGoesFirst) {
    const VirtualMapLayout layout{1024, 128};
    std::vector<uint32_t> pixels(size_t(layout.tableWidth() * layout.tableHeight()), 0);
    pixels[layout.cell(0, 0, 0)] = 1;    // needs level 0; 3 levels short under the top page
    pixels[layout.cell(2, 1, 1)] = 100;  // needs level 2; 1 level short
    PageAllocation a = allocatePages(layout, pixels, 3);
    EXPECT_EQ(a.requested, 5);
    EXPECT_EQ(a.dropped, 2);
    EXPECT_GE(a.table[layout.cell(2, 0, 0)], 0);
    EXPECT_GE(a.table[layout.cell(1, 0, 0)], 0);
    EXPECT_EQ(a.table[layout.cell(2, 1, 1)], -1);
    // One more slot: the near chain is now 1 level short at level 1, as the crowded page is, and
    // the crowded page has more pixels.
    PageAllocation b = allocatePages(layout, pixels, 4);
    EXPECT_GE(b.table[layout.cell(2, 1, 1)], 0);
    EXPECT_EQ(b.table[layout.cell(0, 0, 0)], -1);
}

const RasterLightStats& lightStats(const RasterResult& r, const std::string& light) {
    for (const RasterLightStats& l : r.stats.lights)
        if (l.name == light) return l;
    throw std::runtime_error("no light " + light);
}

// Pixels where two renders' V differ, among those either sees.
size_t differing(const ChannelImage& a, const ChannelImage& b, const std::string& light) {
    const float* va = a.channel(ch::lightChannel(light, ch::kVisibility));
    const float* vb = b.channel(ch::lightChannel(light, ch::kVisibility));
    size_t n = 0;
    for (size_t i = 0; i < a.pixelCount(); ++i) n += va[i] != vb[i];
    return n;
}

// The fraction of pixels where the render agrees with the oracle (V > 0.5 or not), among those
// the light faces and that are more than `radius` pixels from an oracle shadow boundary.
double agreement(const ChannelImage& oracle, const ChannelImage& raster, const std::string& light,
                 int radius) {
    const int w = oracle.width(), h = oracle.height();
    const float* vo = oracle.channel(ch::lightChannel(light, ch::kVisibility));
    const float* co = oracle.channel(ch::lightChannel(light, ch::kCosine));
    const float* vr = raster.channel(ch::lightChannel(light, ch::kVisibility));
    const float* hit = oracle.channel(ch::kHit);
    auto lit = [&](int x, int y) { return vo[size_t(y) * size_t(w) + size_t(x)] > 0.5f; };
    size_t counted = 0, agree = 0;
    for (int y = radius; y < h - radius; ++y)
        for (int x = radius; x < w - radius; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (hit[i] == 0.0f || co[i] <= 0.0f) continue;
            bool nearBoundary = false;
            for (int dy = -radius; dy <= radius && !nearBoundary; ++dy)
                for (int dx = -radius; dx <= radius && !nearBoundary; ++dx)
                    nearBoundary = hit[size_t(y + dy) * size_t(w) + size_t(x + dx)] != 0.0f &&
                                   lit(x + dx, y + dy) != lit(x, y);
            if (nearBoundary) continue;
            ++counted;
            agree += lit(x, y) == (vr[i] > 0.5f);
        }
    EXPECT_GT(counted, size_t(w) * size_t(h) / 10) << light;
    return counted ? double(agree) / double(counted) : 0.0;
}

// Every page at level 0 (density far above need) and a pool that holds them all: the same texels
// and depths as a slope-bias map of the virtual size, so the same V; only the cropped
// projection's rounding may move a texel's coverage, at triangle edges.
TEST(Adaptive, ReproducesSlopeBiasWhenEveryPageIsAtLevelZero) {
    REQUIRE_GL();
    Scene s = makeSquareOccluderScene(320, 240).scene;
    s.lights = {s.lights[1], s.lights[2]};  // spot and sun (the point light has no virtual map)
    RasterResult a = renderOneFrame(
        s, "adaptive", {"virtual_size=1024", "page_size=128", "pool_mb=64", "density=1024"});
    RasterResult b = renderOneFrame(s, "slope-bias", {"resolution=1024", "depth_format=32"});
    for (const Light& l : s.lights) {
        const RasterLightStats& st = lightStats(a, l.name);
        EXPECT_EQ(st.counts.at("pages_dropped"), 0) << l.name;
        EXPECT_EQ(st.counts.at("finest_level_rendered"), 0) << l.name;
        EXPECT_EQ(st.counts.at("levels"), 4) << l.name;
        EXPECT_GT(st.counts.at("pages_marked"), 4) << l.name;
        EXPECT_EQ(st.passes, (std::vector<std::string>{"mark", "pages", "refine", "visibility"}));
        const size_t diff = differing(a.image, b.image, l.name);
        std::printf("[ adaptive ] %s: %zu of %zu pixels differ from slope-bias, %lld pages\n",
                    l.name.c_str(), diff, a.image.pixelCount(),
                    (long long)st.counts.at("pages_rendered"));
        EXPECT_LE(diff, a.image.pixelCount() / 2000) << l.name;
        // The same texel, so the same predicted aliasing.
        const float* aa = a.image.channel(ch::lightChannel(l.name, ch::kPredictedAliasing));
        const float* ab = b.image.channel(ch::lightChannel(l.name, ch::kPredictedAliasing));
        for (size_t i = 0; i < a.image.pixelCount(); ++i)
            ASSERT_NEAR(aa[i], ab[i], 1e-5f * std::max(1.0f, ab[i])) << l.name << " pixel " << i;
    }
}

// The texel used follows the pixel's footprint: with every page resident the predicted aliasing
// stays within (1/2, 1] of 1/density wherever the virtual map is fine enough, while a plain map's
// varies many-fold over the same pixels; and V stays right.
TEST(Adaptive, TexelsFollowTheFootprintAtAGrazingView) {
    REQUIRE_GL();
    Scene s = makeGroundPostsScene(320, 240);
    RasterResult a = renderOneFrame(s, "adaptive", {"virtual_size=65536", "pool_mb=256"});
    RasterResult b = renderOneFrame(s, "slope-bias", {"resolution=4096"});
    const RasterLightStats& st = lightStats(a, "sun");
    std::printf("[ adaptive ] grazing: %lld marked, %lld requested, %lld rendered, %lld dropped\n",
                (long long)st.counts.at("pages_marked"), (long long)st.counts.at("pages_requested"),
                (long long)st.counts.at("pages_rendered"),
                (long long)st.counts.at("pages_dropped"));
    EXPECT_EQ(st.counts.at("pages_dropped"), 0);
    EXPECT_GE(st.counts.at("levels_marked"), 3);
    const float* aa = a.image.channel(ch::lightChannel("sun", ch::kPredictedAliasing));
    const float* ab = b.image.channel(ch::lightChannel("sun", ch::kPredictedAliasing));
    size_t n = 0, inBand = 0;
    float lo = 1e30f, hi = 0.0f;
    for (size_t i = 0; i < a.image.pixelCount(); ++i) {
        if (!(ab[i] > 0.0f)) continue;
        ++n;
        inBand += aa[i] > 0.5f - 1e-3f && aa[i] <= 1.0f + 1e-3f;
        lo = std::min(lo, ab[i]);
        hi = std::max(hi, ab[i]);
    }
    std::printf("[ adaptive ] %zu of %zu pixels in the band; slope-bias 4096 aliasing %g..%g\n",
                inBand, n, double(lo), double(hi));
    EXPECT_GT(n, a.image.pixelCount() / 2);
    EXPECT_GE(double(inBand), 0.95 * double(n));
    EXPECT_GT(hi / lo, 16.0f);
    ChannelImage oracle = runQuiet(s);
    EXPECT_GE(agreement(oracle, a.image, "sun", 2), 0.995);
}

// A pool of 16 pages cannot hold what the camera asks for: pages are dropped, their pixels fall
// back to coarser resident pages, and V is still a sound, if coarser, shadow.
TEST(Adaptive, ASmallPoolDropsPagesAndFallsBackToCoarserOnes) {
    REQUIRE_GL();
    Scene s = makeGroundPostsScene(320, 240);
    RasterResult a = renderOneFrame(s, "adaptive", {"virtual_size=65536", "pool_mb=1", "refine=0"});
    const RasterLightStats& st = lightStats(a, "sun");
    EXPECT_EQ(st.counts.at("pool_pages"), 16);
    EXPECT_EQ(st.counts.at("pages_rendered"), 16);
    EXPECT_GT(st.counts.at("pages_dropped"), 0);
    EXPECT_EQ(st.counts.at("pages_requested"),
              st.counts.at("pages_rendered") + st.counts.at("pages_dropped"));
    ChannelImage oracle = runQuiet(s);
    RasterResult coarse = renderOneFrame(s, "slope-bias", {"resolution=512"});
    const double ag = agreement(oracle, a.image, "sun", 3),
                 ac = agreement(oracle, coarse.image, "sun", 3);
    std::printf("[ adaptive ] 16 pages: agreement %.4f (slope-bias 512: %.4f)\n", ag, ac);
    EXPECT_GE(ag, 0.98);
    EXPECT_GE(ag, ac - 0.002);
}

// With a pool too small for every page, refine=1 spends the second half of the pool only where the
// first half's pages put a shadow edge: fewer pages asked for, and V as good or better.
TEST(Adaptive, EdgeRefinementAsksOnlyNearShadowEdges) {
    REQUIRE_GL();
    Scene s = makeGroundPostsScene(320, 240);
    RasterResult plain = renderOneFrame(s, "adaptive", {"pool_mb=1", "refine=0"});
    RasterResult refined = renderOneFrame(s, "adaptive", {"pool_mb=1", "refine=1"});
    const RasterLightStats& st = lightStats(refined, "sun");
    std::printf("[ adaptive ] refine: %lld requested (%lld by footprint), %lld rendered\n",
                (long long)st.counts.at("pages_requested"),
                (long long)st.counts.at("pages_requested_by_footprint"),
                (long long)st.counts.at("pages_rendered"));
    EXPECT_EQ(lightStats(plain, "sun").counts.at("pages_requested"),
              st.counts.at("pages_requested_by_footprint"));
    EXPECT_LT(st.counts.at("pages_requested"), st.counts.at("pages_requested_by_footprint"));
    ChannelImage oracle = runQuiet(s);
    const double ap = agreement(oracle, plain.image, "sun", 2),
                 ar = agreement(oracle, refined.image, "sun", 2);
    std::printf("[ adaptive ] agreement away from boundaries %.4f -> %.4f\n", ap, ar);
    EXPECT_GE(ar, ap - 0.001);
}

// A point light has no virtual map: a slope-bias cube map of 32-bit depth in the pool's memory.
TEST(Adaptive, PointLightsFallBackToACubeMapOfThePoolsMemory) {
    REQUIRE_GL();
    Scene s = makeSquareOccluderScene(200, 150).scene;
    s.lights = {s.lights[0]};
    RasterResult a = renderOneFrame(s, "adaptive", {"pool_mb=6", "slope_factor=2"});
    const RasterLightStats& st = lightStats(a, "point");
    // sqrt(6 MiB / 24) = 512 texels a face.
    EXPECT_EQ(st.counts.at("cube_fallback"), 1);
    EXPECT_EQ(st.counts.at("cube_resolution"), 512);
    EXPECT_EQ(st.map, "cube");
    EXPECT_EQ(st.passes, (std::vector<std::string>{"shadow_map", "visibility"}));
    RasterResult b =
        renderOneFrame(s, "slope-bias", {"resolution=512", "depth_format=32", "slope_factor=2"});
    EXPECT_EQ(differing(a.image, b.image, "point"), 0u);
}

TEST(Adaptive, MemoryIsThePoolTablesAndMarkTarget) {
    REQUIRE_GL();
    Scene s = makeSquareOccluderScene(160, 120).scene;
    s.lights = {s.lights[2]};
    for (const auto& [settings, poolPages] : std::vector<std::pair<std::vector<std::string>, int>>{
             {{"virtual_size=16384", "page_size=128", "pool_mb=16"}, 256},
             {{"virtual_size=16384", "page_size=128", "pool_mb=3"}, 48},    // 6 x 8 pages
             {{"virtual_size=4096", "page_size=256", "pool_mb=5"}, 20}}) {  // 4 x 5
        RasterResult r = renderOneFrame(s, "adaptive", settings);
        const RasterLightStats& st = lightStats(r, "sun");
        const std::string page = settings[1].substr(10), virt = settings[0].substr(13);
        const uint64_t ps = std::stoull(page), pages0 = std::stoull(virt) / ps;
        uint64_t rows = 0;
        for (uint64_t n = pages0; n >= 1; n /= 2) rows += n;
        const uint64_t pixels = 160 * 120;
        EXPECT_EQ(st.counts.at("pool_pages"), poolPages);
        // Pool (32-bit depth) + request counts and page table (32 bits a cell) + the mark depth
        // buffer (32 bits), + the light's V and aliasing target (renderer: 8 bytes a pixel).
        EXPECT_EQ(st.memoryBytes,
                  uint64_t(poolPages) * ps * ps * 4 + pages0 * rows * 8 + pixels * 4 + pixels * 8)
            << settings[2];
    }
}

TEST(Adaptive, RejectsBadParameters) {
    for (const std::vector<std::string>& bad :
         std::vector<std::vector<std::string>>{{"virtual_size=1000"},
                                               {"virtual_size=131072"},
                                               {"page_size=16"},
                                               {"page_size=96"},
                                               {"virtual_size=256", "page_size=512"},
                                               {"pool_mb=0"},
                                               {"pool_mb=2048"},
                                               {"page_size=1024", "pool_mb=3"},
                                               {"density=0"},
                                               {"fit=2"},
                                               {"resolution=1024"}})
        EXPECT_THROW(createTechnique("adaptive", bad), InputError) << bad.back();
    EXPECT_NO_THROW(createTechnique("adaptive", {"virtual_size=256", "page_size=256"}));
    EXPECT_NO_THROW(createTechnique("adaptive", {"page_size=1024", "pool_mb=4"}));
}

// The claim, on the shipped large terrain (camera near the ground looking to the horizon):
// a 16 MiB pool gives smaller p95 boundary displacement than one 4096² map (64 MiB at 32 bits).
// The full table (2048 to 8192, cascades, 64 MiB) is docs/benchmarks.md's, by
// scripts/resolution-table.
TEST(Adaptive, SixteenMebibytesBeatOne4096MapOnTheLargeTerrain) {
    REQUIRE_GL();
    const Scene scene = loadScene(std::string(SO_SCENES_DIR) + "/large_terrain.scene.json");
    const ChannelImage oracle = runQuiet(scene);
    RasterOptions o;
    o.frames = 1, o.warmup = 0;
    const RasterResult adaptive =
        renderRaster(scene, *createTechnique("adaptive", {"pool_mb=16"}), o, *gl);
    const RasterResult single =
        renderRaster(scene, *createTechnique("slope-bias", {"resolution=4096"}), o, *gl);
    const uint64_t mib = uint64_t(1) << 20;
    // The pool is 16 MiB; with the page tables, the mark pass's depth and the light's targets the
    // technique holds about 24 MiB, under half of the single map's.
    EXPECT_EQ(adaptive.stats.lights[0].counts.at("pool_pages") * 128 * 128 * 4, int64_t(16 * mib));
    EXPECT_LT(adaptive.stats.lights[0].memoryBytes, 32 * mib);
    EXPECT_GE(single.stats.lights[0].memoryBytes, 64 * mib);
    const LightMetrics a = computeLightMetrics(oracle, adaptive.image, "sun", MetricOptions{}),
                       b = computeLightMetrics(oracle, single.image, "sun", MetricOptions{});
    std::printf(
        "p95 boundary displacement: adaptive 16 MiB %.2f px (mean %.2f), slope-bias 4096 "
        "%.2f px (mean %.2f)\n",
        a.boundaryDisplacement.p95, a.boundaryDisplacement.mean, b.boundaryDisplacement.p95,
        b.boundaryDisplacement.mean);
    EXPECT_FALSE(a.boundaryDisplacement.missingBoundary);
    EXPECT_GT(b.boundaryDisplacement.pixels, 1000u) << "the scene has shadow edges to measure";
    EXPECT_LT(a.boundaryDisplacement.p95, b.boundaryDisplacement.p95);
}

}  // namespace
}  // namespace so::test
