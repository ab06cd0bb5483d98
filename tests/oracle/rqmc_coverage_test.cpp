// The oracle's penumbra intervals for disk and sphere lights, which have no closed form here (on a
// floor, and on a plane whose horizon cuts the light: the clipped samplers), against an
// independent reference: 10^6 uniform samples by area of the light per pixel (the verifier's
// sampler, oracle/reference_light.h, with Embree rays from the receiver triangle), on 300 penumbra
// pixels chosen by the reference alone. The stated 95% intervals must cover the reference on 92%
// to 98% of them, and the realised RMS error must be 0.8 to 1.25 of the stated standard error,
// both at a fixed count and adaptively. Then (the Stopping tests) the adaptive intervals' coverage
// over many seeds where stopping decides most (issue 42).
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "core/lights/make_light.h"
#include "embree/embree_handles.h"
#include "lambert.h"
#include "oracle/accel.h"
#include "oracle/area_shadow.h"
#include "oracle/exact_penumbra.h"
#include "oracle/reference_light.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

// A light 4 above the floor, a 2 x 2 square occluder at 1.5 between: wide penumbrae. `tilted`: the
// receiver is instead a plane through the light's centre, so its horizon cuts the light for every
// pixel (the clipped samplers), with a strip occluder in front of it.
Scene makeScene(const Light& l, bool tilted) {
    Scene sc;
    if (!tilted) {
        sc.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 4, "floor"));
        sc.meshes.push_back(makeGrid({0, 1.5, 0}, {2, 0, 0}, {0, 0, -2}, 1, "occluder"));
    } else {
        const glm::dvec3 n = glm::normalize(glm::dvec3(0.15, 0.5, 1.0));
        const glm::dvec3 centre(0.5, -1.0, 2.75);  // n . (centre - light centre) = 0
        const glm::dvec3 t1 = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), n)),
                         t2 = glm::cross(n, t1);
        sc.meshes.push_back(makeGrid(centre, 8.0 * t1, 6.0 * t2, 6, "tilted"));
        sc.meshes.push_back(makeGrid({0.0, 1.5, 2.3}, {2, 0, 0}, {0, 0, -1}, 1, "strip"));
        sc.camera.wsEye = centre + 7.0 * n + glm::dvec3(0, 1.0, 0);
        sc.camera.wsTarget = centre;
    }
    sc.lights = {l};
    sc.effects = {"penumbra"};
    if (!tilted) {
        sc.camera.wsEye = {0.25, 6.0, 5.0};
        sc.camera.wsTarget = {0.25, 0.0, 0.0};
    }
    sc.camera.vfovDeg = 40;
    sc.camera.width = 96;
    sc.camera.height = 72;
    finalizeScene(sc);
    return sc;
}

// V = sum G v / sum G over `n` independent samples, the ray from the receiver point (skipping its
// own triangle) to the light point.
double referenceV(const Accel& accel, const Light& l, const glm::dvec3& p, const glm::dvec3& n,
                  unsigned originId, uint64_t seed, int count) {
    SplitMix rng{seed};
    const ReferenceLight light(l, accel.frame());
    const glm::dvec3 lsP = accel.frame().lsFromWs(p);
    double sw = 0.0, swv = 0.0;
    for (int k = 0; k < count; ++k) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        glm::dvec3 lsY, ny;
        light.point(u1, u2, lsY, ny);
        const glm::dvec3 d = lsY - lsP;
        const double dist2 = glm::dot(d, d), dist = std::sqrt(dist2);
        const glm::dvec3 w = d / dist;
        const double g = std::max(0.0, glm::dot(n, w)) * std::max(0.0, -glm::dot(ny, w)) / dist2;
        if (g <= 0.0) continue;
        RTCRay ray{};
        ray.org_x = float(lsP.x), ray.org_y = float(lsP.y), ray.org_z = float(lsP.z);
        ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
        ray.tnear = 0.0f;
        ray.tfar = 0.9999f;  // stop short of the light's surface
        ray.mask = 0xFFFFFFFFu;
        ray.id = originId;
        ShadowContext ctx = accel.shadowContext(/*coherent=*/false);
        ctx.originFilter(true);  // the ray leaves from the surface itself
        rtcOccluded1(accel.rtcScene(), &ctx.rtc, &ray);
        sw += g;
        swv += ray.tfar >= 0.0f ? g : 0.0;
    }
    return sw > 0.0 ? swv / sw : 0.0;
}

struct Pixel {
    size_t index;
    glm::dvec3 p, n;
    unsigned originId;
    double reference = 0.0;
};

// Up to 300 pixels that the reference (4,096 samples, its own stream) puts in the penumbra.
std::vector<Pixel> penumbraPixels(const Accel& accel, const Light& l, const ChannelImage& img) {
    std::vector<Pixel> candidates;
    const float* A = img.channel(ch::kHit);
    for (size_t i = 0; i < img.pixelCount(); i += 3) {
        if (A[i] == 0.0f) continue;
        Pixel px{i,
                 {img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]},
                 {img.channel(ch::kNX)[i], img.channel(ch::kNY)[i], img.channel(ch::kNZ)[i]},
                 accel.originId(unsigned(img.channel(ch::kMeshId)[i]),
                                unsigned(img.channel(ch::kPrimId)[i]))};
        candidates.push_back(px);
    }
    tbb::parallel_for(size_t(0), candidates.size(), [&](size_t k) {
        Pixel& c = candidates[k];
        c.reference = referenceV(accel, l, c.p, c.n, c.originId, 0x5eed0000u + c.index, 4096);
    });
    std::vector<Pixel> chosen;
    for (const Pixel& c : candidates)
        if (c.reference > 0.03 && c.reference < 0.97 && chosen.size() < 300) chosen.push_back(c);
    return chosen;
}

struct Calibration {
    double coverage, rmsOverStated;
};

Calibration calibrate(const std::vector<Pixel>& pixels, const ChannelImage& img) {
    const float* V = img.channel(ch::lightChannel("L", ch::kVisibility));
    const float* SE = img.channel(ch::lightChannel("L", ch::kStdErr));
    size_t covered = 0;
    double sumSq = 0.0, sumVar = 0.0;
    for (const Pixel& px : pixels) {
        const double e = V[px.index] - px.reference;
        covered += std::fabs(e) <= kIntervalQuantile95 * SE[px.index];
        sumSq += e * e;
        sumVar += double(SE[px.index]) * SE[px.index];
    }
    return {double(covered) / double(pixels.size()), std::sqrt(sumSq / sumVar)};
}

TEST(Rqmc, DiskAndSphereIntervalsCoverAnIndependentReference) {
    const glm::dvec3 center{0.5, 4.0, 0.25};
    const Light disk = diskLight("L", center, {0, -1, 0}, 0.9),
                sphere = sphereLight("L", center, 0.9);
    for (const auto& [light, tilted] :
         {std::pair{disk, false}, {sphere, false}, {disk, true}, {sphere, true}}) {
        const Scene scene = makeScene(light, tilted);
        const std::string what =
            std::string(lightTypeName(light.type)) + (tilted ? ", horizon across" : "");
        EmbreeDevice device;
        const Accel accel(scene, device);
        OracleOptions adaptive;
        adaptive.penumbra.method = PenumbraMethod::Sampled;  // the sampled intervals' coverage
        const ChannelImage adaptiveImg = runOracle(scene, adaptive).image;
        std::vector<Pixel> pixels = penumbraPixels(accel, scene.lights[0], adaptiveImg);
        ASSERT_GE(pixels.size(), 250u) << what;
        tbb::parallel_for(size_t(0), pixels.size(), [&](size_t k) {
            Pixel& px = pixels[k];
            px.reference = referenceV(accel, scene.lights[0], px.p, px.n, px.originId,
                                      0xabc00000u + px.index, 1000000);
        });
        OracleOptions fixed = adaptive;
        fixed.area.fixedSpp = 256;
        const Calibration a = calibrate(pixels, adaptiveImg),
                          f = calibrate(pixels, runOracle(scene, fixed).image);
        std::printf(
            "[ rqmc ] %s: %zu penumbra pixels against 10^6 independent samples each: "
            "adaptive (target 0.01) coverage %.4f, RMS / stated %.3f; 256 spp coverage "
            "%.4f, RMS / stated %.3f\n",
            what.c_str(), pixels.size(), a.coverage, a.rmsOverStated, f.coverage, f.rmsOverStated);
        for (const Calibration& c : {a, f}) {
            EXPECT_GE(c.coverage, 0.92) << what;
            EXPECT_LE(c.coverage, 0.98) << what;
            EXPECT_GE(c.rmsOverStated, 0.8) << what;
            EXPECT_LE(c.rmsOverStated, 1.25) << what;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Coverage after adaptive stopping (issue 42): the stated 95% intervals over many seeds at pixels
// whose V is known, where the stopping rule decides most: a tight target on the closed-form rect
// scene, and a sphere light cut by the receiver's horizon behind a thin rope (the Dutch ship's
// lantern without the asset), whose truth is the exact pass's guaranteed bound (+- 1e-6).

// P(X <= k) for X ~ Binomial(n, p), summed in log space.
double binomialCdf(uint64_t k, uint64_t n, double p) {
    double sum = 0.0;
    for (uint64_t i = 0; i <= k; ++i) {
        const double logTerm = std::lgamma(double(n) + 1.0) - std::lgamma(double(i) + 1.0) -
                               std::lgamma(double(n - i) + 1.0) + double(i) * std::log(p) +
                               double(n - i) * std::log1p(-p);
        sum += std::exp(logTerm);
    }
    return std::min(1.0, sum);
}

struct Interval {
    bool covers;
    double z2, spp;
};

struct Coverage {
    uint64_t intervals = 0, covered = 0;
    double sumZ2 = 0.0, sppSum = 0.0;
    double rate() const { return intervals ? double(covered) / double(intervals) : 0.0; }
    double meanZ2() const { return intervals ? sumZ2 / double(intervals) : 0.0; }
};

Coverage coverageOf(const std::vector<Interval>& all, double maxSpp) {
    Coverage c;
    for (const Interval& i : all)
        if (i.spp <= maxSpp)
            ++c.intervals, c.covered += i.covers, c.sumZ2 += i.z2, c.sppSum += i.spp;
    return c;
}

// The stated intervals of one oracle image at the pixels whose truth is known (NaN elsewhere).
void addIntervals(const ChannelImage& img, const std::string& light,
                  const std::vector<double>& truth, std::vector<Interval>& out) {
    const float* V = img.channel(ch::lightChannel(light, ch::kVisibility));
    const float* SE = img.channel(ch::lightChannel(light, ch::kStdErr));
    const float* spp = img.channel(ch::lightChannel(light, ch::kSpp));
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (std::isnan(truth[i])) continue;
        const double e = V[i] - truth[i];
        out.push_back({std::fabs(e) <= kIntervalQuantile95 * SE[i],
                       SE[i] > 0.0f ? e * e / (double(SE[i]) * SE[i]) : 0.0, spp[i]});
    }
}

void print(const Coverage& c, const std::string& what) {
    std::printf("[ stopping ] %s: %llu intervals, coverage %.4f, mean z^2 %.3f, mean spp %.0f\n",
                what.c_str(), (unsigned long long)c.intervals, c.rate(), c.meanZ2(),
                c.sppSum / double(std::max<uint64_t>(1, c.intervals)));
}

// The intervals are independent (each pixel and seed has its own scrambles), so where each covers
// with probability >= 0.95 the count is at least Binomial(n, 0.95): the check fails when so few
// covered has probability below 1e-3, its false-alarm rate.
void expectNominalCoverage(const Coverage& c, const std::string& what) {
    print(c, what);
    const double p = binomialCdf(c.covered, c.intervals, 0.95);
    std::printf("[ stopping ]   P(Binomial(n, 0.95) <= covered) = %.3g\n", p);
    EXPECT_GE(c.intervals, 1000u) << what;
    EXPECT_GT(p, 1e-3) << what << ": the stated intervals under-cover";
}

TEST(Stopping, ClosedFormRectIntervalsCoverAtATightTarget) {
    const PenumbraScene s = makePenumbraScene(32, 24);
    OracleOptions o;
    o.penumbra.method =
        PenumbraMethod::Sampled;  // the sampled pass's intervals (auto is the default)
    o.area.targetError = 1e-3;
    std::vector<double> exact;
    std::vector<Interval> intervals;
    for (uint32_t seed = 1; seed <= 12; ++seed) {
        o.area.seed = seed;
        const ChannelImage img = runOracle(s.scene, o).image;
        if (exact.empty()) {
            exact.assign(img.pixelCount(), NAN);
            for (size_t i = 0; i < img.pixelCount(); ++i) {
                if (img.channel(ch::kHit)[i] == 0.0f) continue;
                const glm::dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i],
                                   img.channel(ch::kPZ)[i]),
                    n(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i], img.channel(ch::kNZ)[i]);
                const double v = exactRectLightRectOccluderV(p, n, s.light, s.occluder);
                if (v > 1e-9 && v < 1.0 - 1e-9) exact[i] = v;  // the penumbra and its fringe
            }
        }
        addIntervals(img, "panel", exact, intervals);
    }
    expectNominalCoverage(coverageOf(intervals, 1e30), "closed-form rect, target 0.001");
}

// The lantern without the asset: a sphere light whose lower part is below the floor's horizon
// (its centre 0.2 above the floor, radius 0.35), a rope (a 0.012-thick square bar) between it and
// the floor, so the floor's pixels see the light's visible cap cut by the horizon and a sliver of
// it hidden by the rope: V near 0.97, met by few samples.
Scene ropeAndLowSphere() {
    Scene sc;
    sc.meshes.push_back(makeGrid({1.5, 0, 0}, {6, 0, 0}, {0, 0, -6}, 4, "floor"));
    sc.meshes.push_back(makeBox({0.9, 0.14, -3.0}, {0.912, 0.152, 3.0}, "rope"));
    sc.lights = {sphereLight("lantern", {0.0, 0.2, 0.0}, 0.35)};
    sc.effects = {"penumbra"};
    sc.camera.wsEye = {1.9, 2.5, 0.6};
    sc.camera.wsTarget = {1.9, 0.0, 0.0};
    sc.camera.vfovDeg = 30;
    sc.camera.width = 32;
    sc.camera.height = 24;
    finalizeScene(sc);
    return sc;
}

// The pixels that stop early are where optional stopping bites: there the adaptive intervals
// must cover as well as a fixed count's do (whose only error is the t interval's own
// approximation with few hits per replica: 94.7% at 512 samples here). Before the split (one
// spread for the decision and the statement) they covered 85.5% (3,962 of them, 40 seeds) and
// this test failed; after it, 94.0% (5,204).
TEST(Stopping, SphereCutByTheHorizonBehindARopeCovers) {
    const Scene scene = ropeAndLowSphere();
    OracleOptions exactRun;
    exactRun.penumbra.method = PenumbraMethod::Exact;
    const ChannelImage truthImg = runOracle(scene, exactRun).image;
    const float* tV = truthImg.channel("lantern.V");
    const float* tBound = truthImg.channel(ch::lightChannel("lantern", ch::kBound));
    std::vector<double> truth(truthImg.pixelCount(), NAN);
    for (size_t i = 0; i < truth.size(); ++i)
        if (tBound[i] > 0.0f && tBound[i] <= 1e-5f && tV[i] > 0.001f && tV[i] < 0.999f)
            truth[i] = tV[i];
    std::vector<Interval> adaptive, fixed;
    for (uint32_t seed = 1; seed <= 40; ++seed) {
        OracleOptions o;
        o.penumbra.method = PenumbraMethod::Sampled;
        o.area.seed = seed;
        addIntervals(runOracle(scene, o).image, "lantern", truth, adaptive);
        o.area.fixedSpp = 512;
        addIntervals(runOracle(scene, o).image, "lantern", truth, fixed);
    }
    expectNominalCoverage(coverageOf(adaptive, 1e30), "rope and low sphere, target 0.01");
    const Coverage early = coverageOf(adaptive, 1024.0), f = coverageOf(fixed, 1e30);
    print(early, "  of them stopped at <= 1,024 samples");
    print(f, "  a fixed 512 samples");
    ASSERT_GE(early.intervals, 1000u);
    // Two proportions: the early intervals' coverage below the fixed count's by more than 3.09
    // standard errors of the difference (one-sided, false-alarm rate 1e-3).
    const double a = early.rate(), b = f.rate();
    const double se =
        std::sqrt(a * (1 - a) / double(early.intervals) + b * (1 - b) / double(f.intervals));
    EXPECT_GT(a - b, -3.09 * se) << "optional stopping: the intervals of early stops under-cover";
}

}  // namespace
}  // namespace so::test
