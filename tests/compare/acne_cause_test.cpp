// Acne classed by its cause (docs/metrics.md): where the raster says what its own depth comparison
// saw (NAME.map_depth, NAME.receiver_depth, NAME.map_texel and, after a screen-space pass,
// NAME.V_unfiltered), a false shadow is acne only where that comparison shadowed the pixel by its
// own surface, and screen-space bleed where the comparison lit it. Synthetic pairs with the answer
// known by construction; tests/gl/raster_acne_cause_test.cpp renders the two causes.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "raster_compare/compare/metrics.h"

namespace so {
namespace {

namespace ch = channels;

constexpr int kW = 64, kH = 48;
constexpr float kTexel = 0.01f;  // the map texel at every receiver, world units
constexpr float kDepth = 5.0f;   // every receiver's light-space depth

// Every pixel hits triangle 0 of mesh 0 and is fully lit in the oracle, with n.l = cosTheta; a
// shadowed block in the middle gives boundaries to stay away from. The raster agrees, and where
// `probe` says what its comparison saw: the map holding the receiver's own surface at its depth.
struct Pair {
    ChannelImage oracle{kW, kH}, raster{kW, kH};
};

ChannelImage base(float cosTheta) {
    ChannelImage img(kW, kH);
    img.addChannel(ch::kHit, 1.0f);
    for (const char* c : {ch::kPX, ch::kPY, ch::kPZ, ch::kNX, ch::kNZ}) img.addChannel(c, 0.0f);
    img.addChannel(ch::kNY, 1.0f);
    img.addChannel(ch::kDepth, 1.0f);
    img.addChannel(ch::kMeshId, 0.0f);
    img.addChannel(ch::kPrimId, 0.0f);
    img.addChannel(ch::lightChannel("L", ch::kCosine), cosTheta);
    float* V = img.addChannel(ch::lightChannel("L", ch::kVisibility), 1.0f);
    for (int y = 20; y < 28; ++y)
        for (int x = 28; x < 36; ++x) V[size_t(y) * kW + size_t(x)] = 0.0f;
    return img;
}

Pair makePair(float cosTheta, bool probe, bool unfiltered) {
    Pair p{base(cosTheta), base(cosTheta)};
    if (probe) {
        p.raster.addChannel(ch::lightChannel("L", ch::kMapDepth), kDepth);
        p.raster.addChannel(ch::lightChannel("L", ch::kReceiverDepth), kDepth);
        p.raster.addChannel(ch::lightChannel("L", ch::kMapTexel), kTexel);
    }
    if (unfiltered) {
        const float* V = p.raster.channel(ch::lightChannel("L", ch::kVisibility));
        std::copy_n(V, p.raster.pixelCount(),
                    p.raster.addChannel(ch::lightChannel("L", ch::kVisibilityUnfiltered)));
    }
    return p;
}

float& at(ChannelImage& img, const char* suffix, int x, int y) {
    return img.channel(ch::lightChannel("L", suffix))[size_t(y) * kW + size_t(x)];
}

// The false-shadow pixels every test paints: far from the block's boundary (more than r = 2).
constexpr int kFalse[][2] = {{5, 5}, {10, 40}, {50, 8}, {58, 42}, {15, 20}, {45, 30}};
constexpr size_t kFalseCount = std::size(kFalse);

// The pixels the oracle calls fully lit more than 2 pixels from its boundary: acne's denominator.
size_t acneEligible(const ChannelImage& oracle) {
    const float* V = oracle.channel(ch::lightChannel("L", ch::kVisibility));
    size_t n = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (V[size_t(y) * kW + size_t(x)] != 1.0f) continue;
            // The boundary: the lit pixels 4-adjacent to the block.
            double d = 1e9;
            for (int t = 20; t < 28; ++t)
                d = std::min({d, std::hypot(x - 27, y - t), std::hypot(x - 36, y - t)});
            for (int t = 28; t < 36; ++t)
                d = std::min({d, std::hypot(x - t, y - 19), std::hypot(x - t, y - 28)});
            if (d > 2.0) ++n;
        }
    return n;
}

// Paints the false shadows, the map's depth at them `inFront` texels in front of the receiver,
// and their comparison's own V.
void paint(Pair& p, float inFront, float unfilteredV) {
    for (const auto& [x, y] : kFalse) {
        at(p.raster, ch::kVisibility, x, y) = 0.0f;
        if (p.raster.has(ch::lightChannel("L", ch::kMapDepth)))
            at(p.raster, ch::kMapDepth, x, y) = kDepth - inFront * kTexel;
        if (p.raster.has(ch::lightChannel("L", ch::kVisibilityUnfiltered)))
            at(p.raster, ch::kVisibilityUnfiltered, x, y) = unfilteredV;
    }
}

size_t drawnAs(const ErrorMaps& maps, Artifact a) {
    return size_t(std::count(maps.shown.begin(), maps.shown.end(), uint8_t(1 + size_t(a))));
}

// Without the channels (an external image, a technique that compares no depth) the geometric rule
// stays: every painted pixel is acne, and screen-space bleed does not apply.
TEST(AcneByCause, WithoutTheChannelsTheGeometricRuleStays) {
    Pair p = makePair(1.0f, false, false);
    paint(p, 0.0f, 1.0f);
    const LightMetrics m = computeLightMetrics(p.oracle, p.raster, "L", {});
    EXPECT_DOUBLE_EQ(m.acneRate, double(kFalseCount) / double(acneEligible(p.oracle)));
    EXPECT_FALSE(m.screenBleedRate);
    EXPECT_FALSE(m.toJson()["screen_bleed_rate"].is_number());
}

// The map at the pixel's own texel holds its own surface (a third of a texel in front, within the
// margin of one texel at normal incidence): the surface shadowed itself, acne.
TEST(AcneByCause, ItsOwnSurfaceInTheMapIsAcne) {
    Pair p = makePair(1.0f, true, false);
    paint(p, 0.3f, 0.0f);
    ErrorMaps maps;
    const LightMetrics m = computeLightMetrics(p.oracle, p.raster, "L", {}, &maps);
    EXPECT_DOUBLE_EQ(m.acneRate, double(kFalseCount) / double(acneEligible(p.oracle)));
    EXPECT_EQ(m.otherFalseShadowRate, 0.0);
    EXPECT_EQ(drawnAs(maps, Artifact::Acne), kFalseCount);
    EXPECT_FALSE(m.screenBleedRate);  // V is the comparison's own: no screen-space pass
}

// The map holds something five texels in front: a separate occluder's shadow where the oracle sees
// none is not the surface shadowing itself. It is "other false shadow".
TEST(AcneByCause, ASeparateOccluderInTheMapIsNotAcne) {
    Pair p = makePair(1.0f, true, false);
    paint(p, 5.0f, 0.0f);
    ErrorMaps maps;
    const LightMetrics m = computeLightMetrics(p.oracle, p.raster, "L", {}, &maps);
    EXPECT_EQ(m.acneRate, 0.0);
    EXPECT_DOUBLE_EQ(m.otherFalseShadowRate, double(kFalseCount) / double(kW * kH));
    EXPECT_EQ(drawnAs(maps, Artifact::OtherFalseShadow), kFalseCount);
}

// The margin grows with the slope: at n.l = 0.2 (tan theta 4.9) a plane's depth changes by 4.9
// texels per texel across the map, so a map depth 4 texels in front is still the surface's own
// (margin 5.9 texels), and 7 texels in front is not.
TEST(AcneByCause, TheMarginFollowsTheSlope) {
    const double eligible = double(acneEligible(base(0.2f)));
    for (const auto& [inFront, acne] : {std::pair{4.0f, true}, std::pair{7.0f, false}}) {
        Pair p = makePair(0.2f, true, false);
        paint(p, inFront, 0.0f);
        const LightMetrics m = computeLightMetrics(p.oracle, p.raster, "L", {});
        EXPECT_DOUBLE_EQ(m.acneRate, acne ? double(kFalseCount) / eligible : 0.0) << inFront;
    }
}

// Where nothing was compared (-1, -1, texel 0) or the receiver lay beyond the map (+inf), the
// comparison did not shadow it: not acne.
TEST(AcneByCause, NoComparisonIsNotAcne) {
    for (float stored : {-1.0f, std::numeric_limits<float>::infinity()}) {
        Pair p = makePair(1.0f, true, false);
        paint(p, 0.0f, 0.0f);
        for (const auto& [x, y] : kFalse) {
            at(p.raster, ch::kMapDepth, x, y) = stored;
            if (stored < 0.0f) {
                at(p.raster, ch::kReceiverDepth, x, y) = -1.0f;
                at(p.raster, ch::kMapTexel, x, y) = 0.0f;
            }
        }
        const LightMetrics m = computeLightMetrics(p.oracle, p.raster, "L", {});
        EXPECT_EQ(m.acneRate, 0.0) << stored;
    }
}

// After a screen-space pass (NAME.V_unfiltered): a false shadow whose own comparison lit it was
// carried over by the pass, screen-space bleed, even though the map at its texel holds its own
// surface; one whose comparison shadowed it stays acne.
TEST(AcneByCause, ScreenSpaceBleedWhereItsOwnComparisonLit) {
    for (float unfilteredV : {1.0f, 0.0f}) {
        Pair p = makePair(1.0f, true, true);
        paint(p, 0.3f, unfilteredV);
        ErrorMaps maps;
        const LightMetrics m = computeLightMetrics(p.oracle, p.raster, "L", {}, &maps);
        const bool bleed = unfilteredV == 1.0f;
        ASSERT_TRUE(m.screenBleedRate);
        EXPECT_DOUBLE_EQ(*m.screenBleedRate, bleed ? double(kFalseCount) / double(kW * kH) : 0.0);
        EXPECT_DOUBLE_EQ(m.acneRate,
                         bleed ? 0.0 : double(kFalseCount) / double(acneEligible(p.oracle)));
        EXPECT_EQ(drawnAs(maps, Artifact::ScreenBleed), bleed ? kFalseCount : 0u);
        EXPECT_EQ(drawnAs(maps, Artifact::Acne), bleed ? 0u : kFalseCount);
        EXPECT_EQ(m.otherFalseShadowRate, 0.0);
        EXPECT_DOUBLE_EQ(m.toJson()["screen_bleed_rate"].get<double>(), *m.screenBleedRate);
    }
}

// A filtered map's own partial V (pcf's kernel: 0.6 at a pixel the oracle lights) that no
// screen-space pass touched (V equal to V_unfiltered) is the comparison's own false shadow: acne,
// as without V_unfiltered, not bleed; the march darkening the same pixel to 0 makes it bleed.
TEST(AcneByCause, AFilteredMapsOwnPartialVIsNotBleed) {
    for (float finalV : {0.6f, 0.0f}) {
        Pair p = makePair(1.0f, true, true);
        // An area light (stderr 0: exact): a V of 0.6 where the oracle says 1 is a false shadow.
        p.oracle.addChannel(ch::lightChannel("L", ch::kStdErr), 0.0f);
        paint(p, 0.3f, 0.6f);
        for (const auto& [x, y] : kFalse) at(p.raster, ch::kVisibility, x, y) = finalV;
        const LightMetrics m = computeLightMetrics(p.oracle, p.raster, "L", {});
        const bool bleed = finalV < 0.6f;
        ASSERT_TRUE(m.screenBleedRate);
        EXPECT_DOUBLE_EQ(*m.screenBleedRate, bleed ? double(kFalseCount) / double(kW * kH) : 0.0);
        EXPECT_DOUBLE_EQ(m.acneRate,
                         bleed ? 0.0 : double(kFalseCount) / double(acneEligible(p.oracle)));
    }
}

}  // namespace
}  // namespace so
