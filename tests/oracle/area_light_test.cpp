// Area lights: the sampled shadow factor against Lambert's closed form, its confidence intervals,
// convergence, adaptive effort, and the effects switches.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <set>
#include <thread>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "core/lights/make_light.h"
#include "core/sobol.h"
#include "lambert.h"
#include "oracle/area_shadow.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

struct OracleRun {
    ChannelImage img;
    OracleStats stats;
};

OracleRun run(const Scene& scene, const AreaSampling& area, int threads = 0) {
    OracleOptions o;
    o.threads = threads;
    o.area = area;
    o.penumbra.method = PenumbraMethod::Sampled;  // these tests are about the sampled pass
    OracleResult r = runOracle(scene, o);
    return {std::move(r.image), std::move(r.stats)};
}

struct Exact {
    std::vector<double> v;  // per pixel, NaN where no hit
};

Exact exactImage(const PenumbraScene& s, const ChannelImage& img) {
    Exact e;
    e.v.assign(img.pixelCount(), NAN);
    const float* A = img.channel(ch::kHit);
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        glm::dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]);
        glm::dvec3 n(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i], img.channel(ch::kNZ)[i]);
        e.v[i] = exactRectLightRectOccluderV(p, n, s.light, s.occluder);
    }
    return e;
}

bool isPenumbra(double v) {
    return v > 1e-9 && v < 1.0 - 1e-9;
}

// Two-sided p of a Student-t statistic with 7 degrees of freedom (the oracle's 8 replicas), in
// closed form for odd degrees of freedom: P(|T| <= t) = 2/pi (a + sin a (cos a + 2/3 cos^3 a +
// 8/15 cos^5 a)), a = atan(t / sqrt(7)).
double studentT7TwoSidedP(double t) {
    const double a = std::atan(std::fabs(t) / std::sqrt(7.0)), c = std::cos(a);
    const double inside =
        2.0 / M_PI * (a + std::sin(a) * (c + 2.0 / 3.0 * c * c * c + 8.0 / 15.0 * std::pow(c, 5)));
    return std::max(0.0, 1.0 - inside);
}

TEST(Sampling, StudentTQuantileAndP) {
    EXPECT_NEAR(studentT7TwoSidedP(kIntervalQuantile95), 0.05, 1e-9);
    EXPECT_NEAR(studentT7TwoSidedP(0.0), 1.0, 1e-12);
}

TEST(AreaLight, ClosedFormPenumbraWithinStatedIntervals) {
    PenumbraScene s = makePenumbraScene(112, 84);
    OracleRun r = run(s.scene, AreaSampling{});  // default target 0.01
    Exact exact = exactImage(s, r.img);
    const float* V = r.img.channel("panel.V");
    const float* SE = r.img.channel("panel.stderr");
    double absSum = 0.0, penAbs = 0.0;
    size_t hits = 0, penumbra = 0, covered = 0, umbra = 0, lit = 0;
    double minP = 1.0;
    for (size_t i = 0; i < r.img.pixelCount(); ++i) {
        if (std::isnan(exact.v[i])) continue;
        ++hits;
        absSum += std::fabs(V[i] - exact.v[i]);
        if (!isPenumbra(exact.v[i])) {
            (exact.v[i] == 0.0 ? umbra : lit) += 1;
            continue;
        }
        ++penumbra;
        penAbs += std::fabs(V[i] - exact.v[i]);
        covered += std::fabs(V[i] - exact.v[i]) <= kIntervalQuantile95 * SE[i];
        if (SE[i] > 0) minP = std::min(minP, studentT7TwoSidedP((V[i] - exact.v[i]) / SE[i]));
    }
    const double mae = absSum / double(hits);
    ASSERT_TRUE(r.stats.lights[0].area);
    const double coverage = double(covered) / double(penumbra);
    // Sidak: the family of `penumbra` per-pixel tests at significance 0.01.
    const double sidak = 1.0 - std::pow(1.0 - 0.01, 1.0 / double(penumbra));
    std::printf(
        "[ closed form ] %zu pixels (%zu penumbra, %zu umbra, %zu lit): mean |V - exact| = %.5f "
        "(penumbra %.5f), coverage of 95%% intervals = %.4f, smallest p = %.3g (Sidak threshold "
        "%.3g), mean spp %.1f\n",
        hits, penumbra, umbra, lit, mae, penAbs / double(penumbra), coverage, minP, sidak,
        r.stats.lights[0].area->sppMean());
    ASSERT_GT(penumbra, 1000u);
    ASSERT_GT(umbra, 200u);
    // The stated accuracy is the real one: nominal coverage (not 100%), and a mean error near
    // the standard error the target implies (0.8 of it for normal errors), not far below.
    EXPECT_GE(coverage, 0.92);
    EXPECT_LE(coverage, 0.98);
    const double seAtTarget = 0.01 / kIntervalQuantile95;
    EXPECT_LE(penAbs / double(penumbra), seAtTarget);
    EXPECT_GE(penAbs / double(penumbra), 0.2 * seAtTarget) << "intervals far too wide";
    EXPECT_GT(minP, sidak);
}

// A tilted receiver whose horizon cuts the light for many pixels: the horizon-clipped sampling
// path, against the same closed form (which clips the light polygon exactly).
TEST(AreaLight, TiltedReceiverCutByTheHorizon) {
    PenumbraScene s = makePenumbraScene(96, 72);
    // On a plane the horizon is the plane itself, so it cuts the light only if the plane passes
    // through the light. This one contains the light's centre and crosses it obliquely (the
    // visible part is a trapezoid, split into triangles of unequal area); a strip occluder just in
    // front of the plane (z in [1.8, 2.8] at y = 1.5; the plane is at z <= 1.73 there) shadows
    // part of the visible half for the lower receivers.
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.15, 0.5, 1.0));
    const glm::dvec3 lightCentre(0.5, 4.0, 0.25);
    const glm::dvec3 centre(0.5, -1.0, 0.25 - 0.5 * (-1.0 - 4.0));  // on the plane
    ASSERT_NEAR(glm::dot(n, centre - lightCentre), 0.0, 1e-12);
    s.occluder = AxisRect{1.5, -1.0, 1.0, 1.8, 2.8};
    s.scene.meshes[1] = makeGrid({0.0, 1.5, 2.3}, {2, 0, 0}, {0, 0, -1}, 1, "strip");
    const glm::dvec3 t1 = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), n)),
                     t2 = glm::cross(n, t1);
    s.scene.meshes[0] = makeGrid(centre, 8.0 * t1, 6.0 * t2, 6, "tilted");
    s.scene.camera.wsEye = centre + 7.0 * n + glm::dvec3(0, 1.0, 0);
    s.scene.camera.wsTarget = centre;
    finalizeScene(s.scene);
    AreaSampling a;
    a.targetError = 0.02;
    OracleRun r = run(s.scene, a);
    Exact exact = exactImage(s, r.img);
    const float* V = r.img.channel("panel.V");
    const float* SE = r.img.channel("panel.stderr");
    const float* mesh = r.img.channel(ch::kMeshId);
    size_t penumbra = 0, covered = 0, cut = 0, cutCovered = 0, hits = 0;
    double absSum = 0.0;
    for (size_t i = 0; i < r.img.pixelCount(); ++i) {
        if (std::isnan(exact.v[i]) || mesh[i] != 0.0f) continue;
        ++hits;
        absSum += std::fabs(V[i] - exact.v[i]);
        glm::dvec3 p(r.img.channel(ch::kPX)[i], r.img.channel(ch::kPY)[i],
                     r.img.channel(ch::kPZ)[i]);
        int above = 0;
        for (double x : {s.light.x0, s.light.x1})
            for (double z : {s.light.z0, s.light.z1})
                above += glm::dot(n, glm::dvec3(x, s.light.y, z) - p) > 0.0;
        const bool horizonCuts = above > 0 && above < 4;
        const bool ok = std::fabs(V[i] - exact.v[i]) <= kIntervalQuantile95 * SE[i] + 1e-6;
        if (horizonCuts) {
            ++cut;
            cutCovered += ok;
        }
        if (isPenumbra(exact.v[i])) {
            ++penumbra;
            covered += ok;
        }
    }
    std::printf(
        "[ tilted ] %zu receiver pixels, %zu with the horizon across the light (%zu within their "
        "interval), "
        "%zu penumbra (%zu within), mean |V - exact| = %.5f\n",
        hits, cut, cutCovered, penumbra, covered, absSum / double(hits));
    ASSERT_GT(cut, 300u) << "the view must show receivers whose horizon cuts the light";
    EXPECT_GE(double(cutCovered) / double(cut), 0.92);
    EXPECT_GE(double(covered) / double(std::max<size_t>(penumbra, 1)), 0.92);
    EXPECT_LE(absSum / double(hits), a.targetError / kIntervalQuantile95);
}

// The stated standard error is the real one at any fixed sample count: over penumbra pixels the
// realised RMS error over the stated standard error lies in [0.8, 1.25], and the 95% intervals
// cover the exact V on 92% to 98% of them. (With the independent-sample variances of old, the
// ratio was 0.07: intervals 14 times too wide.)
TEST(AreaLight, IntervalsSayTheRealAccuracyAtFixedCounts) {
    PenumbraScene s = makePenumbraScene(96, 72);
    Exact exact;
    for (int spp : {64, 256, 1024}) {
        AreaSampling fixed;
        fixed.fixedSpp = spp;
        OracleRun r = run(s.scene, fixed);
        if (exact.v.empty()) exact = exactImage(s, r.img);
        const float* V = r.img.channel("panel.V");
        const float* SE = r.img.channel("panel.stderr");
        double sumSq = 0.0, sumVar = 0.0;
        size_t n = 0, covered = 0;
        for (size_t i = 0; i < r.img.pixelCount(); ++i) {
            if (std::isnan(exact.v[i]) || !isPenumbra(exact.v[i])) continue;
            const double e = V[i] - exact.v[i];
            sumSq += e * e;
            sumVar += double(SE[i]) * SE[i];
            covered += std::fabs(e) <= kIntervalQuantile95 * SE[i];
            ++n;
        }
        ASSERT_GT(n, 1000u);
        const double ratio = std::sqrt(sumSq / sumVar), coverage = double(covered) / double(n);
        std::printf(
            "[ intervals ] %4d spp: RMS error / stated standard error = %.3f, coverage "
            "%.4f over %zu penumbra pixels\n",
            spp, ratio, coverage, n);
        EXPECT_GE(ratio, 0.8) << spp;
        EXPECT_LE(ratio, 1.25) << spp;
        EXPECT_GE(coverage, 0.92) << spp;
        EXPECT_LE(coverage, 0.98) << spp;
    }
}

TEST(AreaLight, UnoccludedLightsGiveExactlyOne) {
    const glm::dvec3 c{0.5, 2.0, 0.25};
    for (const Light& l : {rectLight("L", c, {1.5, 0, 0}, {0, 0, 1.0}),
                           diskLight("L", c, {0, -1, 0}, 0.8), sphereLight("L", c, 0.8)}) {
        Scene sc;
        // A tilted plane: for some pixels part of the light is below the horizon.
        sc.meshes.push_back(makeGrid({0, 0, 0}, {12, 0, 0}, {0, 3, -12}, 6, "plane"));
        sc.lights = {l};
        sc.effects = {"penumbra"};
        sc.camera.wsEye = {0, 9, 9};
        sc.camera.wsTarget = {0, 0, 0};
        sc.camera.width = sc.camera.height = 64;
        finalizeScene(sc);
        AreaSampling fixed;
        fixed.fixedSpp = 48;
        OracleRun r = run(sc, fixed);
        const float* spp = r.img.channel("L.spp");
        const float* V = r.img.channel("L.V");
        size_t sampled = 0;
        for (size_t i = 0; i < r.img.pixelCount(); ++i) {
            if (spp[i] == 0.0f) continue;
            ++sampled;
            ASSERT_EQ(V[i], 1.0f) << lightTypeName(l.type) << " pixel " << i;
        }
        EXPECT_GT(sampled, r.img.pixelCount() / 3) << lightTypeName(l.type);
    }
}

TEST(AreaLight, ConvergenceSlope) {
    PenumbraScene s = makePenumbraScene(64, 48);
    std::vector<double> logN, logErr;
    Exact exact;
    for (int spp : {16, 64, 256, 1024}) {
        AreaSampling fixed;
        fixed.fixedSpp = spp;
        OracleRun r = run(s.scene, fixed);
        if (exact.v.empty()) exact = exactImage(s, r.img);
        const float* V = r.img.channel("panel.V");
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < r.img.pixelCount(); ++i) {
            if (std::isnan(exact.v[i]) || !isPenumbra(exact.v[i])) continue;
            sum += std::fabs(V[i] - exact.v[i]);
            ++n;
        }
        logN.push_back(std::log(double(spp)));
        logErr.push_back(std::log(sum / double(n)));
        std::printf("[ convergence ] %4d spp: mean |V - exact| over %zu penumbra pixels = %.6f\n",
                    spp, n, sum / double(n));
    }
    // Least-squares slope of log error against log spp.
    const double mx = std::accumulate(logN.begin(), logN.end(), 0.0) / 4,
                 my = std::accumulate(logErr.begin(), logErr.end(), 0.0) / 4;
    double sxy = 0, sxx = 0;
    for (int k = 0; k < 4; ++k) {
        sxy += (logN[k] - mx) * (logErr[k] - my);
        sxx += (logN[k] - mx) * (logN[k] - mx);
    }
    const double slope = sxy / sxx;
    std::printf("[ convergence ] log-log slope = %.3f (independent samples would give -0.5)\n",
                slope);
    EXPECT_LE(slope, -0.5);
}

// The target costs what it says: at the default target on the closed-form scene at 200 x 200 the
// estimator of old (independent-sample variances) spent 1,800 samples per pixel on average for a
// realised penumbra error 25 times below the target's; the honest intervals must stop at least five
// times earlier (issue 12).
TEST(AreaLight, AdaptiveSpendsWhatTheTargetNeeds) {
    PenumbraScene s = makePenumbraScene(200, 200);
    OracleRun r = run(s.scene, AreaSampling{});
    ASSERT_TRUE(r.stats.lights[0].area);
    const AreaShadowStats& la = *r.stats.lights[0].area;
    Exact exact = exactImage(s, r.img);
    const float* V = r.img.channel("panel.V");
    const float* SE = r.img.channel("panel.stderr");
    double penAbs = 0.0, penHalfWidth = 0.0;
    size_t pen = 0;
    for (size_t i = 0; i < r.img.pixelCount(); ++i)
        if (!std::isnan(exact.v[i]) && isPenumbra(exact.v[i])) {
            penAbs += std::fabs(V[i] - exact.v[i]);
            penHalfWidth += kIntervalQuantile95 * SE[i];
            ++pen;
        }
    std::printf(
        "[ adaptive ] 200x200, target 0.01: mean %.1f spp (max %llu), %llu rays, penumbra "
        "mean |V - exact| %.5f over %zu pixels, %.2f s\n",
        la.sppMean(), (unsigned long long)la.sppMax, (unsigned long long)la.raysTraced,
        penAbs / double(pen), pen, la.seconds);
    EXPECT_LE(la.sppMean(), 1800.0 / 5.0);
    // Every pixel met the stopping rule (none ran out of budget). The stated half-width comes
    // from the replicas the rule does not read (area_shadow.h), an independent estimate of the
    // same spread, so some pixels state a little more than the target; the penumbra's mean stays
    // within it.
    EXPECT_EQ(la.pixelsUnconverged, 0u);
    EXPECT_LE(penHalfWidth / double(pen), 0.01);
}

// A tight target buys penumbra accuracy; where every sample agrees, the pixel stops at the
// agreement target instead, with the prior's interval stated (it still holds the exact 0 or 1),
// and no pixel is called unconverged for it.
TEST(AreaLight, AgreeingPixelsStopAtTheAgreementTarget) {
    PenumbraScene s = makePenumbraScene(64, 48);
    AreaSampling tight;
    tight.targetError = 0.002;
    OracleRun r = run(s.scene, tight);
    ASSERT_TRUE(r.stats.lights[0].area);
    const AreaShadowStats& la = *r.stats.lights[0].area;
    Exact exact = exactImage(s, r.img);
    const float* V = r.img.channel("panel.V");
    const float* SE = r.img.channel("panel.stderr");
    const float* spp = r.img.channel("panel.spp");
    size_t agreeing = 0, penumbra = 0;
    double agreeingSpp = 0.0, penumbraSpp = 0.0, penumbraHalfWidth = 0.0;
    for (size_t i = 0; i < r.img.pixelCount(); ++i) {
        if (std::isnan(exact.v[i])) continue;
        const double hw = kIntervalQuantile95 * SE[i];
        if (isPenumbra(exact.v[i])) {
            ++penumbra;
            penumbraSpp += spp[i];
            penumbraHalfWidth += hw;
            continue;
        }
        ++agreeing;
        agreeingSpp += spp[i];
        EXPECT_EQ(V[i], float(exact.v[i])) << i;
        EXPECT_LE(hw, tight.agreementTarget) << i;
        EXPECT_GT(hw, 0.5 * tight.agreementTarget) << i << ": stopped later than it had to";
    }
    ASSERT_GT(agreeing, 1000u);
    ASSERT_GT(penumbra, 100u);
    std::printf(
        "[ agreement ] target 0.002: mean spp %.0f in %zu agreeing pixels, %.0f in %zu "
        "penumbra pixels\n",
        agreeingSpp / double(agreeing), agreeing, penumbraSpp / double(penumbra), penumbra);
    // As in AdaptiveSpendsWhatTheTargetNeeds: the rule was met everywhere. The stated
    // half-widths, independent of it, scatter about the target (the rule stops where its own
    // half's estimate, low as often as high, says so): their penumbra mean within 10% of it
    // (measured 0.00207).
    EXPECT_EQ(la.pixelsUnconverged, 0u);
    EXPECT_LE(penumbraHalfWidth / double(penumbra), 1.1 * tight.targetError);
    EXPECT_GE(la.pixelsAgreeing, agreeing);
    EXPECT_GT(penumbraSpp / double(penumbra), 3.0 * agreeingSpp / double(agreeing));
    // With the agreement target at the target, agreeing pixels pay for it as they did before.
    AreaSampling strict = tight;
    strict.agreementTarget = tight.targetError;
    const AreaShadowStats& ls = *run(s.scene, strict).stats.lights[0].area;
    EXPECT_GT(double(ls.samplesAgreeing) / double(ls.pixelsAgreeing),
              4.0 * double(la.samplesAgreeing) / double(la.pixelsAgreeing));
}

// The cost curve is what the run spent: samples grow and the mean stated half-width falls, it ends
// at the run's totals, and the time it predicts for half the target is within 30% of a real run's.
TEST(AreaLight, CostCurvePredictsATighterTarget) {
    PenumbraScene s = makePenumbraScene(128, 96);
    OracleRun r = run(s.scene, AreaSampling{});
    ASSERT_TRUE(r.stats.lights[0].area);
    const AreaShadowStats& a = *r.stats.lights[0].area;
    ASSERT_GE(a.costCurve.size(), 5u);
    // A pixel's stated half-width is a fresh estimate at each packet and can rise a little from
    // one packet to the next (area_shadow.h), so the means fall up to 0.1% noise once most
    // pixels have stopped.
    for (size_t k = 1; k < a.costCurve.size(); ++k) {
        EXPECT_GE(a.costCurve[k].samples, a.costCurve[k - 1].samples);
        EXPECT_LE(a.costCurve[k].meanHalfWidth, 1.001 * a.costCurve[k - 1].meanHalfWidth);
        ASSERT_TRUE(a.costCurve[k].penumbraMeanHalfWidth &&
                    a.costCurve[k - 1].penumbraMeanHalfWidth);
        EXPECT_LE(*a.costCurve[k].penumbraMeanHalfWidth,
                  1.001 * *a.costCurve[k - 1].penumbraMeanHalfWidth);
    }
    EXPECT_EQ(a.costCurve.back().samples, a.samples);
    // The penumbra's mean half-width, as the run ended, is the mean stated half-width of the
    // pixels with 0 < V < 1 in the image, read back from its channels.
    const float* V = r.img.channel("panel.V");
    const float* SE = r.img.channel("panel.stderr");
    double sum = 0.0;
    size_t penumbra = 0;
    for (size_t i = 0; i < r.img.pixelCount(); ++i)
        if (V[i] > 0.0f && V[i] < 1.0f) sum += ch::kStdErrQuantile95 * SE[i], ++penumbra;
    ASSERT_GT(penumbra, 100u);
    EXPECT_NEAR(*a.costCurve.back().penumbraMeanHalfWidth, sum / double(penumbra),
                1e-3 * sum / double(penumbra));
    AreaSampling half;
    half.targetError = 0.005;
    OracleRun tighter = run(s.scene, half);
    const AreaShadowStats& b = *tighter.stats.lights[0].area;
    // Samples rather than seconds: the same prediction, free of the machine's load.
    const std::optional<double> predicted = a.predictedSeconds(0.005);
    ASSERT_TRUE(predicted);
    const double predictedSamples = double(a.samples) * *predicted / a.seconds;
    std::printf(
        "[ cost ] target 0.01: %llu samples; 0.005 predicted %.0f, measured %llu (slope "
        "%.3f)\n",
        (unsigned long long)a.samples, predictedSamples, (unsigned long long)b.samples,
        *a.costSlope());
    EXPECT_NEAR(predictedSamples / double(b.samples), 1.0, 0.3);
}

// A pixel that spends its budget short of the target is marked and counted, not passed off.
TEST(AreaLight, PixelsShortOfTheTargetAreMarked) {
    PenumbraScene s = makePenumbraScene(64, 48);
    AreaSampling tight;
    tight.targetError = 0.002;
    tight.maxSpp = 128;
    OracleRun r = run(s.scene, tight);
    ASSERT_TRUE(r.stats.lights[0].area);
    const AreaShadowStats& la = *r.stats.lights[0].area;
    const float* U = r.img.channel("panel.unconverged");
    const float* SE = r.img.channel("panel.stderr");
    uint64_t marked = 0;
    for (size_t i = 0; i < r.img.pixelCount(); ++i) {
        marked += U[i] == 1.0f;
        if (U[i] == 1.0f) {
            EXPECT_GT(kIntervalQuantile95 * SE[i], tight.targetError) << i;
        }
    }
    EXPECT_EQ(marked, la.pixelsUnconverged);
    EXPECT_GT(marked, la.pixelsSampled / 2) << "128 samples cannot reach 0.002";
    EXPECT_NEAR(la.shareReachedTarget(), 1.0 - double(marked) / double(la.pixelsSampled), 1e-12);
    // A fixed count has no target to miss: no channel.
    AreaSampling fixed;
    fixed.fixedSpp = 32;
    EXPECT_FALSE(run(s.scene, fixed).img.has("panel.unconverged"));
}

TEST(AreaLight, SameImageAtAnyThreadCount) {
    PenumbraScene s = makePenumbraScene(48, 36);
    AreaSampling a;
    a.targetError = 0.03;
    OracleRun ref = run(s.scene, a, 1);
    for (int threads : {2, 5}) {
        OracleRun r = run(s.scene, a, threads);
        for (const std::string& name : ref.img.names())
            EXPECT_EQ(0, std::memcmp(ref.img.channel(name), r.img.channel(name),
                                     ref.img.pixelCount() * sizeof(float)))
                << name << " differs with " << threads << " threads";
    }
    // And a different seed gives different samples.
    a.seed = 7;
    OracleRun other = run(s.scene, a, 1);
    EXPECT_NE(0, std::memcmp(ref.img.channel("panel.V"), other.img.channel("panel.V"),
                             ref.img.pixelCount() * sizeof(float)));
}

// Two oracles at once in one process (a library caller's threads, a Python session's), one at
// fewer threads than cores and one oversubscribed: each gives what it gives alone, bit for bit.
TEST(AreaLight, TwoOraclesAtOnceGiveWhatEachGivesAlone) {
    PenumbraScene s = makePenumbraScene(48, 36);
    AreaSampling a;
    a.targetError = 0.03;
    const OracleRun alone1 = run(s.scene, a, 1), alone7 = run(s.scene, a, 7);
    for (int round = 0; round < 3; ++round) {
        OracleRun at1, at7;
        std::thread first([&] { at1 = run(s.scene, a, 1); });
        std::thread second([&] { at7 = run(s.scene, a, 7); });
        first.join();
        second.join();
        for (const std::string& name : alone1.img.names()) {
            EXPECT_EQ(0, std::memcmp(alone1.img.channel(name), at1.img.channel(name),
                                     alone1.img.pixelCount() * sizeof(float)))
                << name << " differs at 1 thread beside another oracle, round " << round;
            EXPECT_EQ(0, std::memcmp(alone7.img.channel(name), at7.img.channel(name),
                                     alone7.img.pixelCount() * sizeof(float)))
                << name << " differs at 7 threads beside another oracle, round " << round;
        }
    }
}

TEST(Effects, WithoutPenumbraOneRayPerLitFacingPixel) {
    PenumbraScene s = makePenumbraScene(64, 48);
    s.scene.effects = {"hard"};
    OracleRun r = run(s.scene, AreaSampling{});
    const float* A = r.img.channel(ch::kHit);
    const float* C = r.img.channel("panel.cos");
    uint64_t facing = 0;
    for (size_t i = 0; i < r.img.pixelCount(); ++i) facing += A[i] != 0.0f && C[i] > 0.0f;
    const OracleLightStats& l = r.stats.lights[0];
    ASSERT_TRUE(l.hard);
    EXPECT_FALSE(l.sampled());
    EXPECT_EQ(l.hard->raysTraced, facing);
    EXPECT_FALSE(r.img.has("panel.stderr"));
    EXPECT_FALSE(r.img.has("panel.spp"));
    EXPECT_NE(l.method.find("centre"), std::string::npos);
    // A hard light's V is 0 or 1.
    const float* V = r.img.channel("panel.V");
    for (size_t i = 0; i < r.img.pixelCount(); ++i) ASSERT_TRUE(V[i] == 0.0f || V[i] == 1.0f);
}

TEST(Effects, ContactOnlyWhenAsked) {
    Scene sc;
    sc.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 4, "floor"));
    sc.meshes.push_back(makeBox({-1, 0, -1}, {1, 1.5, 1}, "box"));
    sc.lights = {pointLight("key", {2.5, 5.0, 1.5})};
    sc.camera.wsEye = {-5, 6, -6};
    sc.camera.wsTarget = {0, 0.5, 0};
    sc.camera.width = sc.camera.height = 96;
    sc.effects = {"hard"};
    finalizeScene(sc);
    OracleRun without = run(sc, AreaSampling{});
    EXPECT_FALSE(without.img.has("key.occ_dist"));
    EXPECT_EQ(without.stats.closestHitQueries, 0u);

    sc.effects = {"hard", "contact"};
    OracleRun with = run(sc, AreaSampling{});
    ASSERT_TRUE(with.img.has("key.occ_dist"));
    ASSERT_TRUE(with.stats.lights[0].hard);
    EXPECT_EQ(with.stats.closestHitQueries, with.stats.lights[0].hard->raysTraced);
    // Same visibility either way.
    EXPECT_EQ(0, std::memcmp(without.img.channel("key.V"), with.img.channel("key.V"),
                             with.img.pixelCount() * sizeof(float)));
    // The distance to the box along the ray, against a slab test in double.
    const float* D = with.img.channel("key.occ_dist");
    const float* V = with.img.channel("key.V");
    const float* mesh = with.img.channel(ch::kMeshId);
    size_t checked = 0;
    for (size_t i = 0; i < with.img.pixelCount(); ++i) {
        if (mesh[i] != 0.0f || V[i] != 0.0f || D[i] < 0.0f) continue;
        glm::dvec3 p(with.img.channel(ch::kPX)[i], with.img.channel(ch::kPY)[i],
                     with.img.channel(ch::kPZ)[i]);
        glm::dvec3 d = glm::normalize(glm::dvec3(2.5, 5.0, 1.5) - p);
        double t0 = 0, t1 = 1e30;
        const glm::dvec3 lo(-1, 0, -1), hi(1, 1.5, 1);
        for (int k = 0; k < 3; ++k) {
            double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
            t0 = std::max(t0, std::min(a, b));
            t1 = std::min(t1, std::max(a, b));
        }
        if (!(t0 < t1)) continue;  // grazing an edge: the float point may see it differently
        EXPECT_NEAR(D[i], t0, 1e-4 * (1.0 + t0)) << "pixel " << i;
        ++checked;
    }
    EXPECT_GT(checked, 300u);
    // Unoccluded pixels have +inf, untraced -1.
    for (size_t i = 0; i < with.img.pixelCount(); ++i) {
        if (V[i] == 1.0f) {
            ASSERT_TRUE(std::isinf(D[i]));
        }
    }
}

TEST(Effects, WarningsForWhatTheLightsCannotShow) {
    // Checked through the loader: see SceneLoader tests for the files; here the oracle's side:
    // contact rays of a sampled area light go to its centre and are counted separately.
    PenumbraScene s = makePenumbraScene(32, 24);
    s.scene.effects = {"penumbra", "contact"};
    AreaSampling fixed;
    fixed.fixedSpp = 16;
    OracleRun r = run(s.scene, fixed);
    const OracleLightStats& l = r.stats.lights[0];
    ASSERT_TRUE(l.sampled());
    ASSERT_TRUE(l.hard);  // the contact rays
    EXPECT_EQ(l.hard->closestHitQueries, l.hard->raysTraced);
    EXPECT_TRUE(r.img.has("panel.occ_dist"));
}

TEST(Sampling, SixteenSampleBlocksAreStratified) {
    for (uint32_t seed : {0u, 1u, 0xdeadbeefu})
        for (uint32_t block = 0; block < 32; ++block)
            for (int kx : {1, 2, 4, 8, 16}) {
                std::set<int> cells;
                for (uint32_t i = 0; i < 16; ++i) {
                    float u, v;
                    sobol2D(block * 16 + i, seed, u, v);
                    ASSERT_TRUE(u >= 0.0f && u < 1.0f && v >= 0.0f && v < 1.0f);
                    cells.insert(int(u * kx) * 100 + int(v * (16 / kx)));
                }
                ASSERT_EQ(cells.size(), 16u)
                    << "seed " << seed << " block " << block << " " << kx << "x" << 16 / kx;
            }
}

TEST(Sampling, BlockGeneratorMatchesPointByPoint) {
    for (uint32_t seed : {0u, 99u})
        for (uint32_t first : {0u, 16u, 1024u, 65536u + 48u}) {
            float u[16], v[16];
            sobol2DBlock16(first, seed, u, v);
            for (uint32_t k = 0; k < 16; ++k) {
                float a, b;
                sobol2D(first + k, seed, a, b);
                ASSERT_EQ(u[k], a);
                ASSERT_EQ(v[k], b);
            }
        }
}

TEST(Sampling, AllAgreeingSamplesAreNotCertain) {
    // 16 of 16 lit, equal weights: the interval must not collapse to a point.
    RatioEstimate e = ratioEstimate(16, 16, 16, 16, 16);
    EXPECT_EQ(e.V, 1.0);
    EXPECT_NEAR(e.stderr_, 0.066, 0.002);
    // An always-lit pixel reaches a half-width of 0.01 only after ~270 samples.
    int n = 16;
    while (1.96 * ratioEstimate(n, n, n, n, uint64_t(n)).stderr_ > 0.01) n += 16;
    EXPECT_GE(n, 256);
    EXPECT_LE(n, 288);
}

// The arc of a circle above the horizon must never come out short (a sliver of the light would
// never be sampled): the polynomial acos bounds the true one from above, closely, over [-1, 1].
TEST(Sampling, AcosIsATightUpperBound) {
    double worst = 0.0;
    for (int i = 0; i <= 200000; ++i) {
        const float x = std::clamp(-1.0f + float(i) * 1e-5f, -1.0f, 1.0f);
        const double exact = std::acos(double(x)), bound = double(acosUpperBound(x));
        ASSERT_GE(bound, exact) << x;
        worst = std::max(worst, bound - exact);
    }
    for (float x :
         {-1.0f, -0.0f, 0.0f, 1.0f, std::nextafter(1.0f, 0.0f), -std::nextafter(1.0f, 0.0f)})
        EXPECT_GE(double(acosUpperBound(x)), std::acos(double(x))) << x;
    EXPECT_LE(worst, 3e-6);
    EXPECT_LE(acosUpperBound(-1.0f), std::numbers::pi_v<float>);
}

}  // namespace
}  // namespace so::test
