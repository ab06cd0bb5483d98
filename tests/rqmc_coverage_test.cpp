// The oracle's penumbra intervals for disk and sphere lights, which have no closed form here (on a
// floor, and on a plane whose horizon cuts the light: the clipped samplers), against an
// independent reference: 10^6 uniform samples by area of the light per pixel (the verifier's
// sampler, oracle/reference_light.h, with Embree rays from the receiver triangle), on 300 penumbra
// pixels chosen by the reference alone. The stated 95% intervals must cover the reference on 92%
// to 98% of them, and the realised RMS error must be 0.8 to 1.25 of the stated standard error,
// both at a fixed count and adaptively.
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "oracle/accel.h"
#include "oracle/area_shadow.h"
#include "oracle/embree_handles.h"
#include "oracle/reference_light.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

// A light 4 above the floor, a 2 x 2 square occluder at 1.5 between: wide penumbrae. `tilted`: the
// receiver is instead a plane through the light's centre, so its horizon cuts the light for every
// pixel (the clipped samplers), with a strip occluder in front of it.
Scene makeScene(LightType type, bool tilted) {
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
    Light l;
    l.name = "L";
    l.type = type;
    l.wsPosition = {0.5, 4.0, 0.25};
    l.wsNormal = {0, -1, 0};
    l.radius = 0.9;
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
    for (const auto& [type, tilted] : {std::pair{LightType::Disk, false},
                                       {LightType::Sphere, false},
                                       {LightType::Disk, true},
                                       {LightType::Sphere, true}}) {
        const Scene scene = makeScene(type, tilted);
        const std::string what =
            std::string(lightTypeName(type)) + (tilted ? ", horizon across" : "");
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

}  // namespace
}  // namespace so::test
