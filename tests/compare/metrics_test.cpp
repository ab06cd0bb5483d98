// The metric functions on synthetic image pairs whose answers are known by construction.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "raster_compare/compare/metrics.h"

namespace so {
namespace {

namespace ch = channels;

// Every pixel hits triangle 0 of mesh 0, faces the light, and is lit; callers paint V.
ChannelImage flatImage(int w, int h) {
    ChannelImage img(w, h);
    img.addChannel(ch::kHit, 1.0f);
    for (const char* c : {ch::kPX, ch::kPY, ch::kPZ, ch::kNX, ch::kNZ}) img.addChannel(c, 0.0f);
    img.addChannel(ch::kNY, 1.0f);
    img.addChannel(ch::kDepth, 1.0f);
    img.addChannel(ch::kMeshId, 0.0f);
    img.addChannel(ch::kPrimId, 0.0f);
    img.addChannel(ch::lightChannel("L", ch::kVisibility), 1.0f);
    img.addChannel(ch::lightChannel("L", ch::kCosine), 1.0f);
    return img;
}
float& at(ChannelImage& img, const char* suffix, int x, int y) {
    return img.channel(ch::lightChannel("L", suffix))[size_t(y) * size_t(img.width()) + size_t(x)];
}

TEST(Metrics, ShadowShiftedByKPixelsMeasuresK) {
    for (int k : {1, 3, 8}) {
        ChannelImage o = flatImage(96, 64), r = flatImage(96, 64);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 96; ++x) {
                at(o, ch::kVisibility, x, y) = x < 40 ? 1.0f : 0.0f;
                at(r, ch::kVisibility, x, y) = x < 40 + k ? 1.0f : 0.0f;
            }
        LightMetrics m = computeLightMetrics(o, r, "L", {});
        EXPECT_DOUBLE_EQ(m.boundaryDisplacement.mean, double(k));
        EXPECT_DOUBLE_EQ(m.boundaryDisplacement.p95, double(k));
        EXPECT_DOUBLE_EQ(m.boundaryDisplacement.max, double(k));
        EXPECT_EQ(m.boundaryDisplacement.pixels, 128u);
        EXPECT_DOUBLE_EQ(m.falseLitRate, double(k * 64) / (96.0 * 64.0));
        EXPECT_EQ(m.falseShadowRate, 0.0);
    }
}

TEST(Metrics, InjectedAcneGivesItsDensityAndNoAliasing) {
    ChannelImage o = flatImage(120, 80), r = flatImage(120, 80);
    // A shadow block in the middle, so that there are boundaries to stay away from.
    for (int y = 30; y < 50; ++y)
        for (int x = 50; x < 70; ++x)
            at(o, ch::kVisibility, x, y) = at(r, ch::kVisibility, x, y) = 0.0f;
    MetricOptions opt;
    opt.boundaryRadius = 2;
    size_t eligible = 0, injected = 0;
    for (int y = 0; y < 80; ++y)
        for (int x = 0; x < 120; ++x) {
            if (at(o, ch::kVisibility, x, y) != 1.0f) continue;
            // Brute-force Euclidean distance to the boundary pixels (lit, 4-adjacent to the
            // block): an independent check of the metric's distance transform.
            double d = 1e9;
            for (int t = 30; t < 50; ++t)
                d = std::min({d, std::hypot(x - 49, y - t), std::hypot(x - 70, y - t)});
            for (int t = 50; t < 70; ++t)
                d = std::min({d, std::hypot(x - t, y - 29), std::hypot(x - t, y - 50)});
            if (d <= 2.0) continue;
            ++eligible;
            if ((x * 7 + y * 3) % 10 == 0) {
                at(r, ch::kVisibility, x, y) = 0.0f;
                ++injected;
            }
        }
    LightMetrics m = computeLightMetrics(o, r, "L", opt);
    EXPECT_DOUBLE_EQ(m.acneRate, double(injected) / double(eligible));
    EXPECT_EQ(m.aliasingRate, 0.0);
    EXPECT_GT(injected, 500u);
}

TEST(Metrics, DetachedContactGivesTheInjectedLeakDistance) {
    ChannelImage o = flatImage(100, 40), r = flatImage(100, 40);
    float* occ = o.addChannel(ch::lightChannel("L", ch::kOccluderDistance), -1.0f);
    // Shadow from column 30 on; the occluder is 0.05 units further away per column from there.
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 100; ++x) {
            const size_t i = size_t(y) * 100 + size_t(x);
            if (x >= 30) {
                at(o, ch::kVisibility, x, y) = 0.0f;
                occ[i] = 0.05f * float(x - 30 + 1);
                // The raster shadow starts 6 columns late: detached from the contact.
                at(r, ch::kVisibility, x, y) = x >= 36 ? 0.0f : 1.0f;
            } else {
                occ[i] = std::numeric_limits<float>::infinity();
            }
        }
    MetricOptions opt;
    opt.contactThreshold = 0.5;  // columns 30..38 are "at contact" (occ_dist 0.05 .. 0.45)
    LightMetrics m = computeLightMetrics(o, r, "L", opt);
    ASSERT_TRUE(m.lightLeakDistance && m.peterPanningRate);
    EXPECT_FLOAT_EQ(float(*m.lightLeakDistance), 0.05f * 6.0f);  // the last detached column, 35
    EXPECT_DOUBLE_EQ(*m.peterPanningRate, 6.0 / 9.0);
}

TEST(Metrics, BrighterUmbraGivesTheInjectedBleedingRateForFilteredTechniques) {
    ChannelImage o = flatImage(80, 80), r = flatImage(80, 80);
    size_t umbra = 0, bright = 0;
    for (int y = 0; y < 80; ++y)
        for (int x = 0; x < 80; ++x) {
            if (x < 40) continue;
            at(o, ch::kVisibility, x, y) = 0.0f;
            ++umbra;
            const bool b = (x + y) % 4 == 0;
            at(r, ch::kVisibility, x, y) = b ? 0.3f : 0.05f;  // 0.05: within the 0.1 allowance
            bright += b;
        }
    MetricOptions opt;
    opt.filteredTechnique = true;
    LightMetrics m = computeLightMetrics(o, r, "L", opt);
    ASSERT_TRUE(m.lightBleedingRate);
    EXPECT_DOUBLE_EQ(*m.lightBleedingRate, double(bright) / double(umbra));
    opt.filteredTechnique = false;
    EXPECT_FALSE(computeLightMetrics(o, r, "L", opt).lightBleedingRate)
        << "only measured for filtered techniques";
}

TEST(Metrics, AreaLightIntervalsAndPenumbraBias) {
    ChannelImage o = flatImage(50, 10), r = flatImage(50, 10);
    o.addChannel(ch::lightChannel("L", ch::kStdErr), 0.01f);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 50; ++x) {
            const float v = 0.1f + 0.016f * float(x);  // a ramp, strictly inside (0, 1)
            at(o, ch::kVisibility, x, y) = v;
            // Within the interval (2.3646 * 0.01) on the left half; too hard by 0.1 on the right.
            at(r, ch::kVisibility, x, y) = x < 25 ? v + 0.015f : (v < 0.5f ? v - 0.1f : v + 0.1f);
        }
    LightMetrics m = computeLightMetrics(o, r, "L", {});
    ASSERT_TRUE(m.penumbraMae && m.penumbraBias);
    // Left half: no error; right half: 0.1 - 0.0236 each.
    EXPECT_NEAR(m.mae, 0.5 * (0.1 - ch::kStdErrQuantile95 * 0.01), 1e-6);
    EXPECT_NEAR(*m.penumbraMae, m.mae, 1e-12);
    EXPECT_LT(*m.penumbraBias, -0.04) << "too hard is negative";
}

// Where the prediction says texels are larger, the shadow edge strays further: positive
// correlation; the opposite prediction gives a negative one.
TEST(Metrics, PredictedAliasingCorrelatesWithBoundaryDisplacement) {
    for (bool agree : {true, false}) {
        ChannelImage o = flatImage(96, 64), r = flatImage(96, 64);
        float* AP = r.addChannel(ch::lightChannel("L", ch::kPredictedAliasing), 0.0f);
        for (int y = 0; y < 64; ++y) {
            const int shift = y < 32 ? 1 : 6;
            for (int x = 0; x < 96; ++x) {
                at(o, ch::kVisibility, x, y) = x < 40 ? 1.0f : 0.0f;
                at(r, ch::kVisibility, x, y) = x < 40 + shift ? 1.0f : 0.0f;
                AP[size_t(y) * 96 + size_t(x)] = float(agree ? shift : 7 - shift);
            }
        }
        LightMetrics m = computeLightMetrics(o, r, "L", {});
        ASSERT_TRUE(m.aliasingCorrelation && m.predictedAliasingMean);
        if (agree) {
            EXPECT_GT(*m.aliasingCorrelation, 0.9);
        } else {
            EXPECT_LT(*m.aliasingCorrelation, -0.9);
        }
        EXPECT_DOUBLE_EQ(*m.predictedAliasingMean, 3.5);
    }
}

TEST(Metrics, ExclusionsAreCountedByReason) {
    ChannelImage o = flatImage(10, 10), r = flatImage(10, 10);
    o.channel(ch::kHit)[0] = 0.0f;                             // background
    r.channel(ch::kPrimId)[1] = 5.0f;                          // another triangle
    o.channel(ch::lightChannel("L", ch::kCosine))[2] = -0.5f;  // facing away
    LightMetrics m = computeLightMetrics(o, r, "L", {});
    EXPECT_EQ(m.excludedBackground, 1u);
    EXPECT_EQ(m.excludedDifferentSurface, 1u);
    EXPECT_EQ(m.excludedFacingAway, 1u);
    EXPECT_EQ(m.counted, 97u);
    EXPECT_TRUE(m.toJson().contains("boundary_displacement_px"));
}

// A technique that drops a shadow entirely (or invents one) scores the worst boundary
// displacement there is, the image diagonal, never 0.
TEST(Metrics, MissingShadowScoresTheWorstBoundaryDisplacement) {
    const double diagonal = std::hypot(96.0, 64.0);
    ChannelImage withShadow = flatImage(96, 64), without = flatImage(96, 64),
                 shifted = flatImage(96, 64);
    for (int y = 20; y < 40; ++y)
        for (int x = 30; x < 60; ++x) {
            at(withShadow, ch::kVisibility, x, y) = 0.0f;
            at(shifted, ch::kVisibility, x + 3, y) = 0.0f;
        }
    const LightMetrics dropped = computeLightMetrics(withShadow, without, "L", {});
    EXPECT_TRUE(dropped.boundaryDisplacement.missingBoundary);
    EXPECT_DOUBLE_EQ(dropped.boundaryDisplacement.p95, diagonal);
    EXPECT_NEAR(dropped.boundaryDisplacement.mean, diagonal, 1e-9);
    const LightMetrics invented = computeLightMetrics(without, withShadow, "L", {});
    EXPECT_TRUE(invented.boundaryDisplacement.missingBoundary);
    EXPECT_DOUBLE_EQ(invented.boundaryDisplacement.max, diagonal);
    const LightMetrics near = computeLightMetrics(withShadow, shifted, "L", {});
    EXPECT_FALSE(near.boundaryDisplacement.missingBoundary);
    EXPECT_DOUBLE_EQ(near.boundaryDisplacement.max, 3.0);
    EXPECT_LT(near.boundaryDisplacement.p95, dropped.boundaryDisplacement.p95);
    const LightMetrics none = computeLightMetrics(without, without, "L", {});
    EXPECT_FALSE(none.boundaryDisplacement.missingBoundary) << "no shadow in either: agreement";
    EXPECT_EQ(none.boundaryDisplacement.max, 0.0);
}

// Every wrong pixel is drawn as exactly one class: the drawn pixels add up to the false-shadow and
// false-lit pixels, each drawn class marks that pixel, and "other" counts what no class explains.
TEST(Metrics, EveryWrongPixelHasExactlyOneClass) {
    for (bool area : {false, true}) {
        ChannelImage o = flatImage(120, 90), r = flatImage(120, 90);
        float* D = o.addChannel(ch::lightChannel("L", ch::kOccluderDistance), 0.2f);
        std::fill(D + 120 * 45, D + 120 * 90, 0.9f);  // the lower half is not at contact
        if (area) o.addChannel(ch::lightChannel("L", ch::kStdErr), 0.01f);
        uint32_t state = 12345;
        auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
        for (int y = 0; y < 90; ++y)
            for (int x = 0; x < 120; ++x) {
                const float truth = x < 50 ? 1.0f : x < 60 && area ? 0.1f * float(x - 50) : 0.0f;
                at(o, ch::kVisibility, x, y) = truth;
                const uint32_t k = next() % 10;  // 30% of the pixels wrong in some way
                at(r, ch::kVisibility, x, y) = k == 0   ? 1.0f - truth
                                               : k == 1 ? 0.7f
                                               : k == 2 ? 0.3f
                                                        : truth;
            }
        MetricOptions opt;
        opt.contactThreshold = 0.5;
        opt.filteredTechnique = area;
        ErrorMaps maps;
        const LightMetrics m = computeLightMetrics(o, r, "L", opt, &maps);
        size_t shown = 0, other[2] = {0, 0}, spread = 0;
        for (size_t i = 0; i < maps.shown.size(); ++i) {
            if (!maps.shown[i]) continue;
            ++shown;
            const Artifact a = Artifact(maps.shown[i] - 1);
            EXPECT_EQ(maps.of(a)[i], 1.0f) << "pixel " << i << " is drawn as a class it is not in";
            other[0] += a == Artifact::OtherFalseShadow;
            other[1] += a == Artifact::OtherFalseLit;
            spread += a == Artifact::PenumbraSpread;
        }
        const double counted = double(m.counted);
        EXPECT_NEAR(double(shown), (m.falseShadowRate + m.falseLitRate) * counted, 1e-6) << area;
        EXPECT_NEAR(double(other[0]), m.otherFalseShadowRate * counted, 1e-6);
        EXPECT_NEAR(double(other[1]), m.otherFalseLitRate * counted, 1e-6);
        EXPECT_GT(shown, 2000u);
        EXPECT_GT(other[0] + other[1], 0u) << "the test must exercise the other classes";
        EXPECT_EQ(spread > 0, area) << "soft wrong pixels beside the penumbra: area lights only";
        EXPECT_EQ(m.aliasingRate.has_value(), !area) << "no 0/1 aliasing on area lights";
    }
}

// A soft edge (one pixel at 0.5, as a filter makes it) is no error for the 0/1 threshold metrics
// but counts in the boundary band.
TEST(Metrics, BoundaryBandMaeCreditsSoftEdges) {
    ChannelImage o = flatImage(96, 64), r = flatImage(96, 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 96; ++x) {
            at(o, ch::kVisibility, x, y) = x < 40 ? 1.0f : 0.0f;
            at(r, ch::kVisibility, x, y) = x < 40 ? 1.0f : x == 40 ? 0.5f : 0.0f;
        }
    MetricOptions opt;
    opt.boundaryRadius = 2;
    const LightMetrics m = computeLightMetrics(o, r, "L", opt);
    EXPECT_EQ(m.aliasingRate, 0.0);
    EXPECT_EQ(m.falseLitRate, 0.0);
    ASSERT_TRUE(m.boundaryBandMae);
    // The band: columns 37..41 (within 2 of the boundary column 39); one of five is off by 0.5.
    EXPECT_DOUBLE_EQ(*m.boundaryBandMae, 0.5 / 5.0);
}

// Soft edges of known widths: the oracle ramps from 0 to 1 over 40 pixels (a 10%-90% width of 32
// along its gradient, which runs along x), the technique over 20 (16) and as a hard step (0): the
// width errors are 16 and 32 on every profile; the split of the error into umbra, penumbra and lit
// pixels, and the sign of the bias (too hard < 0 < too soft).
TEST(Metrics, PenumbraWidthUmbraAndLit) {
    const int W = 160, H = 12;
    auto ramp = [](int x, double centre, double width) {
        return float(std::clamp((double(x) + 0.5 - centre) / width + 0.5, 0.0, 1.0));
    };
    for (const auto& [width, expected] : {std::pair{20.0, 16.0}, std::pair{0.0, 32.0}}) {
        ChannelImage o = flatImage(W, H), r = flatImage(W, H);
        o.addChannel(ch::lightChannel("L", ch::kStdErr), 1e-4f);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                at(o, ch::kVisibility, x, y) = ramp(x, 80.0, 40.0);
                at(r, ch::kVisibility, x, y) =
                    width > 0.0 ? ramp(x, 80.0, width) : (x < 80 ? 0.0f : 1.0f);
            }
        const LightMetrics m = computeLightMetrics(o, r, "L", {});
        ASSERT_TRUE(m.penumbraWidth) << width;
        EXPECT_EQ(m.penumbraWidth->profiles, size_t(H)) << width;
        EXPECT_NEAR(m.penumbraWidth->oracleMeanWidth, 32.0, 0.5) << width;
        EXPECT_NEAR(m.penumbraWidth->mean, expected, 0.5) << width;
        EXPECT_NEAR(m.penumbraWidth->p95, expected, 0.5) << width;
        ASSERT_TRUE(m.umbraMae && m.litMae && m.penumbraBias);
        EXPECT_EQ(*m.umbraMae, 0.0);
        EXPECT_EQ(*m.litMae, 0.0);
        EXPECT_LT(*m.penumbraBias, 0.0) << "narrower than the truth is too hard";
    }
    // Too soft is positive, and a wrong umbra or lit pixel counts there.
    ChannelImage o = flatImage(W, H), r = flatImage(W, H);
    o.addChannel(ch::lightChannel("L", ch::kStdErr), 1e-4f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            at(o, ch::kVisibility, x, y) = ramp(x, 80.0, 20.0);
            at(r, ch::kVisibility, x, y) = ramp(x, 80.0, 40.0);
        }
    const LightMetrics m = computeLightMetrics(o, r, "L", {});
    ASSERT_TRUE(m.penumbraBias && m.umbraMae && m.litMae && m.penumbraWidth);
    EXPECT_GT(*m.penumbraBias, 0.0) << "wider than the truth is too soft";
    EXPECT_GT(*m.umbraMae, 0.0);
    EXPECT_GT(*m.litMae, 0.0);
    EXPECT_NEAR(m.penumbraWidth->mean, 16.0, 0.5);
}

// No oracle interval (a hard light): none of the area-light metrics.
TEST(Metrics, PenumbraMetricsOnlyForAreaLights) {
    ChannelImage o = flatImage(40, 8), r = flatImage(40, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 40; ++x) at(o, ch::kVisibility, x, y) = x < 20 ? 0.0f : 1.0f;
    const LightMetrics m = computeLightMetrics(o, r, "L", {});
    EXPECT_FALSE(m.penumbraWidth || m.umbraMae || m.litMae || m.penumbraMae ||
                 m.penumbraSpreadRate);
}

// Penumbra spread (docs/metrics.md): soft edges across x on a 160 x 24 view. The oracle's
// penumbra is columns 70..89 (V = 0 left of it, 1 right of it, and its 0.5 contour at column 80,
// so every fully lit pixel is more than r from it); the technique's own edge is another ramp.
constexpr int kSpreadW = 160, kSpreadH = 24;

// V of a linear edge `width` pixels wide centred at `centre` (a step where width is 0).
float edgeV(int x, double centre, double width) {
    return float(std::clamp((double(x) + 0.5 - centre) / width + 0.5, 0.0, 1.0));
}

// The oracle of the spread tests, with an area light's interval (stderr) unless `hard`; the
// technique's image paints its own edge, centred at `centre`, `width` wide.
std::pair<ChannelImage, ChannelImage> spreadPair(double centre, double width, bool hard = false) {
    ChannelImage o = flatImage(kSpreadW, kSpreadH), r = flatImage(kSpreadW, kSpreadH);
    if (!hard) o.addChannel(ch::lightChannel("L", ch::kStdErr), 1e-4f);
    for (int y = 0; y < kSpreadH; ++y)
        for (int x = 0; x < kSpreadW; ++x) {
            at(o, ch::kVisibility, x, y) = edgeV(x, 80.0, 20.0);
            at(r, ch::kVisibility, x, y) = edgeV(x, centre, width);
        }
    return {std::move(o), std::move(r)};
}

// Pixels drawn as the class, and pixels its layer marks.
std::pair<size_t, size_t> drawnAndMarked(const ErrorMaps& maps, Artifact a) {
    size_t drawn = 0, marked = 0;
    for (size_t i = 0; i < maps.shown.size(); ++i) {
        drawn += maps.shown[i] == 1 + size_t(a);
        marked += maps.of(a)[i] == 1.0f;
    }
    return {drawn, marked};
}

// A technique's penumbra three times as wide as the truth, on the same midline: its false shadow
// on the oracle's fully lit columns 90..109 and its false light on the umbra's 50..69 are the
// penumbra spreading, not acne (before schema_version 6, acne_rate was 20 / 70 here).
TEST(Metrics, OverWidePenumbraIsPenumbraSpreadNotAcne) {
    const auto [o, r] = spreadPair(80.0, 60.0);
    ErrorMaps maps;
    const LightMetrics m = computeLightMetrics(o, r, "L", {}, &maps);
    ASSERT_TRUE(m.penumbraSpreadRate);
    EXPECT_DOUBLE_EQ(*m.penumbraSpreadRate, 40.0 / kSpreadW);
    EXPECT_EQ(m.acneRate, 0.0);
    EXPECT_EQ(m.otherFalseShadowRate, 0.0);
    EXPECT_EQ(m.otherFalseLitRate, 0.0);
    const size_t spread = 40 * kSpreadH;
    EXPECT_EQ(drawnAndMarked(maps, Artifact::PenumbraSpread), std::make_pair(spread, spread));
    EXPECT_EQ(drawnAndMarked(maps, Artifact::Acne), std::make_pair(size_t(0), size_t(0)));
    EXPECT_EQ(m.toJson()["penumbra_spread_rate"], *m.penumbraSpreadRate);
}

// A penumbra of the right width moved by 8 pixels, either way: the 8 columns it leaves wrong
// outside the oracle's penumbra (false shadow on the lit side, false light in the umbra) are
// spread; neither acne nor "other".
TEST(Metrics, ShiftedPenumbraIsPenumbraSpreadNotAcne) {
    for (const double shift : {8.0, -8.0}) {
        const auto [o, r] = spreadPair(80.0 + shift, 20.0);
        ErrorMaps maps;
        const LightMetrics m = computeLightMetrics(o, r, "L", {}, &maps);
        ASSERT_TRUE(m.penumbraSpreadRate) << shift;
        EXPECT_DOUBLE_EQ(*m.penumbraSpreadRate, 8.0 / kSpreadW) << shift;
        EXPECT_EQ(m.acneRate, 0.0) << shift;
        EXPECT_EQ(m.otherFalseShadowRate + m.otherFalseLitRate, 0.0) << shift;
        // The other 20 wrong columns are the oracle's penumbra, drawn as such.
        EXPECT_DOUBLE_EQ(shift > 0 ? m.falseShadowRate : m.falseLitRate, 28.0 / kSpreadW) << shift;
        EXPECT_EQ(drawnAndMarked(maps, Artifact::Penumbra).first, size_t(20 * kSpreadH)) << shift;
        EXPECT_EQ(drawnAndMarked(maps, Artifact::PenumbraSpread).first, size_t(8 * kSpreadH));
    }
}

// A surface shadowing itself stays acne, soft (R = 0.6, a filtered map's acne) or hard (R = 0),
// however near the penumbra: speckles on the lit side, one of them two pixels from the penumbra's
// last column; a surface acned all over that touches the penumbra across its edge (another mesh,
// as the soft_chair's back above its seat); and a face of the same mesh across a crease.
TEST(Metrics, SelfShadowingNextToAPenumbraStaysAcne) {
    auto [o, r] = spreadPair(80.0, 20.0);  // the technique right everywhere but below
    size_t acne = 0;
    const std::pair<int, int> speckles[] = {{92, 10}, {110, 8}, {120, 8}, {130, 12}, {140, 12}};
    for (const auto& [x, y] : speckles) {
        at(r, ch::kVisibility, x, y) = x % 20 == 0 ? 0.0f : 0.6f;
        ++acne;
    }
    for (int y = 0; y < kSpreadH; ++y)
        for (int x = 90; x < kSpreadW; ++x) {
            const size_t i = size_t(y) * kSpreadW + size_t(x);
            if (y < 6) {  // rows 0..5: another mesh, in both images
                o.channel(ch::kMeshId)[i] = r.channel(ch::kMeshId)[i] = 1.0f;
            } else if (y >= 18) {  // rows 18..23: a face turned 90 degrees from the penumbra's
                o.channel(ch::kNX)[i] = 1.0f;
                o.channel(ch::kNY)[i] = 0.0f;
            } else {
                continue;
            }
            at(r, ch::kVisibility, x, y) = 0.6f;
            ++acne;
        }
    ErrorMaps maps;
    const LightMetrics m = computeLightMetrics(o, r, "L", {}, &maps);
    ASSERT_TRUE(m.penumbraSpreadRate);
    EXPECT_EQ(*m.penumbraSpreadRate, 0.0);
    EXPECT_EQ(acne, 5u + 2u * 6u * 70u);
    EXPECT_DOUBLE_EQ(m.acneRate, double(acne) / (70.0 * kSpreadH));  // columns 90..159 eligible
    EXPECT_EQ(drawnAndMarked(maps, Artifact::Acne), std::make_pair(acne, acne));
    // The same acned face without the crease is one surface with the penumbra: there the spread
    // explains it (the test above can fail).
    auto [o2, r2] = spreadPair(80.0, 20.0);
    for (int y = 18; y < kSpreadH; ++y)
        for (int x = 90; x < kSpreadW; ++x) at(r2, ch::kVisibility, x, y) = 0.6f;
    const LightMetrics flat = computeLightMetrics(o2, r2, "L", {});
    EXPECT_EQ(flat.acneRate, 0.0);
    EXPECT_DOUBLE_EQ(*flat.penumbraSpreadRate, 6.0 * 70.0 / (double(kSpreadW) * kSpreadH));
}

// Hard lights keep their classes: no penumbra spread (null, the layer empty), so a soft false
// shadow beyond the 0.5 contour is acne as before, even where the oracle image has values strictly
// between 0 and 1 for the flood to start from.
TEST(Metrics, HardLightsHaveNoPenumbraSpread) {
    const auto [o, r] = spreadPair(95.0, 20.0, true);  // columns 90..94: R < 0.5 where O = 1
    ErrorMaps maps;
    const LightMetrics m = computeLightMetrics(o, r, "L", {}, &maps);
    EXPECT_FALSE(m.penumbraSpreadRate);
    EXPECT_TRUE(m.toJson()["penumbra_spread_rate"].is_null());
    EXPECT_DOUBLE_EQ(m.acneRate, 5.0 / 70.0);
    EXPECT_EQ(drawnAndMarked(maps, Artifact::PenumbraSpread), std::make_pair(size_t(0), size_t(0)));
    EXPECT_EQ(drawnAndMarked(maps, Artifact::Acne).first, size_t(5 * kSpreadH));
}

}  // namespace
}  // namespace so
