// The exact penumbra pass (oracle/polygon_visibility.h, oracle/exact_penumbra.h) against the
// closed form of tests/lambert.h, against the sampled pass's own intervals and independent float64
// estimates on a real mesh, at any thread count and through the command line. Its hard cases are
// in tests/hard_cases/exact_penumbra_cases_test.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bunny_scene.h"
#include "cli_run.h"
#include "core/channels.h"
#include "exact_penumbra_util.h"
#include "lambert.h"
#include "oracle/exact_penumbra.h"
#include "oracle/oracle.h"
#include "oracle/polygon_visibility.h"
#include "oracle/reference_light.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;
using glm::dvec3;

// The closed-form scene's occluder: a 2 x 2 square at height 1.5, parallel to the light.
const AxisRect kOccluder = PenumbraScene{}.occluder;
const AxisRect kLight = kPenumbraLight;

TEST(ExactPenumbra, LambertMatchesTheClosedFormOfAnUnoccludedLight) {
    const RectLightShape l = lightShape(kLight);
    const std::vector<dvec3> rect = {l.corner, l.corner + l.edgeU, l.corner + l.edgeU + l.edgeV,
                                     l.corner + l.edgeV};
    for (const dvec3& p : {dvec3(0.3, 0.0, 0.2), dvec3(-3.0, 0.5, 2.0), dvec3(5.0, 3.9, 0.0)}) {
        const double phi = std::abs(cosineWeightedSolidAngle(p, {0, 1, 0}, rect));
        const double reference = polygonIrradiance(p, {0, 1, 0}, rect, l.emitNormal);
        EXPECT_NEAR(phi, reference, 1e-12 * reference) << p.x;
        // The other winding gives the opposite sign.
        std::vector<dvec3> reversed(rect.rbegin(), rect.rend());
        EXPECT_NEAR(cosineWeightedSolidAngle(p, {0, 1, 0}, reversed),
                    -cosineWeightedSolidAngle(p, {0, 1, 0}, rect), 1e-15);
    }
}

// Issue 31's bar: below 1e-6 of the closed form over every penumbra point, here on a dense grid of
// the floor and on tilted receivers whose horizon cuts the light.
TEST(ExactPenumbra, ClosedFormSquareOccluderWithinOneMillionth) {
    Occluders occ;
    occ.addRect(kOccluder);
    const ExactTracer t = occ.tracer();
    const RectLightShape l = lightShape(kLight);
    double worst = 0.0;
    size_t penumbra = 0, umbra = 0;
    for (const dvec3& n : {dvec3(0, 1, 0), glm::normalize(dvec3(0.9, 0.3, 0.1))}) {
        for (int i = 0; i <= 200; ++i)
            for (int j = 0; j <= 200; ++j) {
                const dvec3 p(-4.0 + 0.04 * i, 0.0, -4.0 + 0.04 * j);
                const double reference = exactRectLightRectOccluderV(p, n, kLight, kOccluder);
                const PolygonVisibility v = visibility(t, l, p, n);
                // The tilted receivers' horizon leaves some points no light at all.
                ASSERT_EQ(v.status, reference == 0.0 && v.V == 0.0 && v.occluders == 0
                                        ? v.status
                                        : PolygonVisibilityStatus::Exact);
                worst = std::max(worst, std::fabs(v.V - reference));
                penumbra += reference > 1e-9 && reference < 1.0 - 1e-9;
                umbra += reference == 0.0;
                if (reference == 0.0) {
                    EXPECT_EQ(v.V, 0.0) << "umbra is exactly 0";
                }
            }
    }
    std::printf("[ exact ] %zu penumbra and %zu umbra points: max |V - closed form| = %.3g\n",
                penumbra, umbra, worst);
    EXPECT_GT(penumbra, 5000u);
    EXPECT_GT(umbra, 1000u);
    EXPECT_LT(worst, 1e-6);
}

// The oracle with --penumbra exact on the closed-form scene: every exact pixel's V within float
// rounding of the closed form at its point, stderr 0 there, and the penumbra pixels all exact.
TEST(ExactPenumbra, OracleExactPixelsMatchTheClosedForm) {
    const PenumbraScene s = makePenumbraScene(112, 84);
    OracleOptions o;
    o.penumbra.method = PenumbraMethod::Exact;
    const OracleResult r = runOracle(s.scene, o);
    const ChannelImage& img = r.image;
    const float* V = img.channel("panel.V");
    const float* SE = img.channel("panel.stderr");
    const float* exact = img.channel("panel.exact");
    ASSERT_NE(exact, nullptr);
    size_t exactPixels = 0;
    double worst = 0.0;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (img.channel(ch::kHit)[i] == 0.0f) continue;
        const dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]);
        const dvec3 n(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i], img.channel(ch::kNZ)[i]);
        const double reference = exactRectLightRectOccluderV(p, n, s.light, s.occluder);
        if (exact[i] != 1.0f) {
            // Not exact: the samples agreed, as the closed form does (lit or umbra).
            EXPECT_TRUE(V[i] == 0.0f || V[i] == 1.0f) << i;
            continue;
        }
        ++exactPixels;
        EXPECT_EQ(SE[i], 0.0f);
        worst = std::max(worst, std::fabs(double(V[i]) - reference));
    }
    const ExactPenumbraStats& st = *r.stats.lights[0].area->exact;
    EXPECT_EQ(st.pixelsExact, exactPixels);
    EXPECT_GT(exactPixels, 1000u);
    // P is stored in float: the closed form at the rounded point differs by about the
    // penumbra's gradient times 2^-24 of the coordinates, plus V's own float rounding.
    std::printf("[ exact ] %zu exact pixels: max |V - closed form at the stored P| = %.3g\n",
                exactPixels, worst);
    EXPECT_LT(worst, 1e-6);
}

// An independent float64 estimate with a standard error: `samples` i.i.d. uniform points of the
// light (SplitMix64, nothing of the oracle's Sobol sequences), each tested with the exact tracer's
// ray test from p, the ratio estimator's standard error by the delta method.
struct Estimate {
    double V = 0.0, stderr_ = 0.0;
};
Estimate randomEstimate(const ExactTracer& t, const RectLightShape& light, const dvec3& p,
                        const dvec3& n, TriangleId self, int samples, uint64_t seed) {
    SplitMix rng{seed};
    double sw = 0.0, swv = 0.0, sw2 = 0.0, sw2v = 0.0;
    for (int k = 0; k < samples; ++k) {
        const double u = double(rng.next() >> 11) * 0x1.0p-53,
                     v = double(rng.next() >> 11) * 0x1.0p-53;
        const dvec3 d = light.corner + u * light.edgeU + v * light.edgeV - p;
        const double r2 = glm::dot(d, d);
        const double w = std::max(0.0, glm::dot(n, d)) *
                         std::max(0.0, -glm::dot(light.emitNormal, d)) / (r2 * r2);
        if (w == 0.0) continue;
        const double lit = t.occluded(p, d, 1e-7, 1.0, self) ? 0.0 : 1.0;
        sw += w, swv += w * lit, sw2 += w * w, sw2v += w * w * lit;
    }
    Estimate e;
    if (sw == 0.0) return e;
    e.V = swv / sw;
    // Var(sum w (v - V)) / (sum w)^2 with (v - V)^2 = v (1 - 2V) + V^2.
    const double residual = sw2v * (1.0 - 2.0 * e.V) + sw2 * e.V * e.V;
    e.stderr_ = std::sqrt(std::max(0.0, residual)) / sw;
    return e;
}

// A real mesh (the Stanford bunny) under a rect light low over it, with pixels where the light is
// near the horizon: the exact V lies within the sampled pass's 95% interval at about the nominal
// rate at 4,096 spp (--penumbra both), and agrees with an independent float64 estimate of 10^6
// samples on a few pixels, within its error.
TEST(ExactPenumbra, BunnyWithinTheSampledIntervalsAndAnIndependentEstimate) {
    std::string why;
    const MeshPrimitive* bunny = cgalBunny(why);
    if (!bunny) GTEST_SKIP() << why;
    Scene scene = makeBunnyScene(*bunny, 80, 60);
    useLowRectLight(scene);
    OracleOptions o;
    o.area.fixedSpp = 4096;
    o.penumbra.method = PenumbraMethod::Both;
    const OracleResult r = runOracle(scene, o);
    const ExactPenumbraStats& st = *r.stats.lights[0].area->exact;
    const double n = double(st.pixelsExact), share = double(st.outsideInterval) / n;
    std::printf(
        "[ exact ] bunny: %llu exact pixels, %.4f outside the sampled 95%% interval, "
        "mean |V_exact - V| %.2e, occluders mean %.1f, max %llu; exact pass %.3f s, sampled "
        "pass (4,096 spp) %.3f s\n",
        (unsigned long long)st.pixelsExact, share, st.sumAbsDifference / n,
        double(st.occludersTotal) / n, (unsigned long long)st.occludersMax, st.seconds,
        r.stats.lights[0].area->seconds);
    ASSERT_GT(st.pixelsExact, 300u);
    // Nominal: at most 5% outside, give or take three binomial standard errors; and some outside,
    // or the intervals would be far wider than they say.
    EXPECT_LE(share, 0.05 + 3.0 * std::sqrt(0.05 * 0.95 / n));
    EXPECT_GT(st.outsideInterval, 0u);

    // The independent estimate, in world space at the stored P (its float rounding moves V by
    // far less than the estimate's error).
    const ChannelImage& img = r.image;
    const float* exact = img.channel("panel.exact");
    const float* Vexact = img.channel("panel.V_exact");
    std::vector<ExactTracer::MeshView> views;
    for (const MeshPrimitive& m : scene.meshes) views.push_back({&m.wsPositions, &m.indices});
    const ExactTracer t(views);
    const RectLightShape shape = rectLightShape(scene.lights[0]);
    std::vector<size_t> penumbra;
    for (size_t i = 0; i < img.pixelCount(); ++i)
        if (exact[i] == 1.0f && Vexact[i] > 0.05f && Vexact[i] < 0.95f) penumbra.push_back(i);
    ASSERT_GE(penumbra.size(), 4u);
    int checked = 0;
    for (size_t k = 0; k < 4; ++k) {
        const size_t i = penumbra[k * penumbra.size() / 4];
        const dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]);
        const dvec3 nrm(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i], img.channel(ch::kNZ)[i]);
        const TriangleId self{uint32_t(img.channel(ch::kMeshId)[i]),
                              uint32_t(img.channel(ch::kPrimId)[i])};
        const Estimate e = randomEstimate(t, shape, p, nrm, self, 1000000, 31 + i);
        std::printf("[ exact ] pixel %zu: V_exact %.5f, estimate %.5f +- %.5f (1 s.e.)\n", i,
                    double(Vexact[i]), e.V, e.stderr_);
        EXPECT_LT(std::fabs(double(Vexact[i]) - e.V), 4.0 * e.stderr_ + 1e-5) << i;
        ++checked;
    }
    EXPECT_EQ(checked, 4);
}

// The same exact image at any thread count, bit for bit (the pass sums in slot order).
TEST(ExactPenumbra, SameImageAtAnyThreadCount) {
    const PenumbraScene s = makePenumbraScene(64, 48);
    std::vector<std::vector<float>> images;
    for (int threads : {1, 2}) {
        OracleOptions o;
        o.threads = threads;
        o.penumbra.method = PenumbraMethod::Both;
        o.penumbra.allPixels = true;
        const OracleResult r = runOracle(s.scene, o);
        const float* v = r.image.channel("panel.V_exact");
        images.emplace_back(v, v + r.image.pixelCount());
    }
    EXPECT_EQ(images[0], images[1]);
}

// The command line: the flags by name, a bad name one line naming its flag.
TEST(ExactPenumbra, CommandLineFlags) {
    const std::string scene = std::string(SO_SCENES_DIR) + "/penumbra_square.scene.json";
    const std::string out = ::testing::TempDir() + "so_exact_cli";
    const RunResult bad = run("trace " + scene + " --out " + out + " --penumbra exakt");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_EQ(bad.stderrText,
              "command line: --penumbra: \"exakt\" is not a method (sampled, exact or both)\n");
    EXPECT_EQ(run("trace " + scene + " --out " + out + " --exact-pixels some").exitCode, 2);
    const RunResult ok = run("trace " + scene + " --out " + out +
                             " --width 48 --height 36 --quiet --penumbra both --exact-pixels all");
    ASSERT_EQ(ok.exitCode, 0) << ok.stderrText;
    const ChannelImage img = readExr(out + "/oracle.exr");
    EXPECT_NE(img.channel("panel.V_exact"), nullptr);
    EXPECT_NE(img.channel("panel.exact"), nullptr);
}

}  // namespace
}  // namespace so::test
