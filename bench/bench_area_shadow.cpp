// Area-light throughput of the oracle against a plain Embree loop over the same rays, and the
// rays adaptive sampling saves against a uniform run at the same worst-pixel half-width.
//
//   bench_area_shadow [--size N] [--spp S] [--reps R] [--adaptive-size M] [--no-adaptive]
//
// On the generated scene of bench_scene.h (167,936 triangles), per light (rect, disk, sphere):
//   oracle    traceAreaShadows at a fixed S spp: per-pixel classification, Sobol sampling of the
//             light, 16-ray packets, the ratio estimator and its interval
//   occ16     rtcOccluded16 over exactly those packets, prepared beforehand, on a plain Embree
//             scene (no origin-triangle filter: the oracle's price includes it)
// interleaved R times (median of per-run ratios), and a count of the pixels where the plain loop's
// hits do not give the oracle's V (self-intersections the filter rejects). Then, at M x M pixels,
// the adaptive run (target 0.01) against a uniform run with as many samples per pixel as the
// adaptive run's hardest pixel.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>

#include "bench_scene.h"
#include "bench_util.h"
#include "core/camera.h"
#include "core/lights/make_light.h"
#include "oracle/area_shadow.h"
#include "oracle/oracle.h"
#include "oracle/surface_buffer.h"

using namespace so;
using namespace so::bench;

namespace {

std::vector<Light> benchLights() {
    return {rectLight("rect", {1, 12, 2}, {4, 0, 0}, {0, 0, 3}),
            diskLight("disk", {1, 12, 2}, {0, -1, 0}, 1.8), sphereLight("sphere", {1, 12, 2}, 1.5)};
}

}  // namespace

int main(int argc, char** argv) {
    int size = 256, spp = 64, reps = 5, adaptiveSize = 128;
    CLI::App app{
        "area-light shadow rays: the oracle against a plain Embree loop over the same rays"};
    app.add_option("--size", size, "image side for the throughput runs")
        ->check(CLI::Range(16, 4096));
    app.add_option("--spp", spp, "samples per pixel for the throughput runs")
        ->check(CLI::Range(16, 4096));
    app.add_option("--reps", reps, "repetitions (median reported)")->check(CLI::Range(1, 100));
    app.add_option("--adaptive-size", adaptiveSize, "image side for adaptive vs uniform")
        ->check(CLI::Range(8, 1024));
    bool noAdaptive = false;
    app.add_flag("--no-adaptive", noAdaptive,
                 "leave out adaptive vs uniform (scripts/oracle-ratios reads the ratios only)");
    bool noNearField = false;
    app.add_flag("--no-near-field", noNearField,
                 "leave the near fields out (their price: the oracle's time with and without)");
    CLI11_PARSE(app, argc, argv);
    Scene scene = makeBenchScene(256, size);
    const int threads = int(std::thread::hardware_concurrency());
    std::printf("scene: %zu triangles, %dx%d pixels, %d spp, %d threads, median of %d runs\n",
                scene.stats.triangles, size, size, spp, threads, reps);
    EmbreeDevice device("threads=0");
    Accel accel(scene, device);
    Accel plain(scene, device, /*originFilter=*/false);
    Camera camera(scene.camera);
    tbb::task_arena arena(threads);
    SurfaceBuffer sb;
    arena.execute([&] { sb = tracePrimary(accel, camera, nullptr); });
    buildNearFieldsTimed(arena, accel, sb, noNearField);
    const size_t n = size_t(sb.width) * size_t(sb.height);
    AreaSampling sampling;
    sampling.fixedSpp = spp;

    int failures = 0;
    for (const Light& light : benchLights()) {
        const AreaLight al = makeAreaLight(light, accel.frame());
        std::vector<float> V(n), SE(n), S(n), C(n);
        AreaShadowStats st;
        auto runOracle = [&] {
            arena.execute([&] {
                st = traceAreaShadows(accel, sb, al, sampling, 0,
                                      {V.data(), SE.data(), S.data(), C.data(), nullptr}, nullptr);
            });
        };
        // The same pass without the near fields (moved aside for the run): their share of the time.
        NearFields aside;
        std::vector<float> V2(n), SE2(n), S2(n), C2(n);
        auto runOracleFar = [&] {
            std::swap(aside, sb.nearFields);
            arena.execute([&] {
                traceAreaShadows(accel, sb, al, sampling, 0,
                                 {V2.data(), SE2.data(), S2.data(), C2.data(), nullptr}, nullptr);
            });
            std::swap(aside, sb.nearFields);
        };
        // The oracle's rays, prepared beforehand in its own order and packets.
        struct alignas(64) Packet {
            RTCRay16 ray;
            int valid[16];
            float weight[16];
            uint32_t pixel;
        };
        std::vector<Packet> packets;
        FacingCache facingCache;
        uint64_t exactDecisions = 0;
        for (size_t s = 0; s < sb.slotCount(); ++s) {
            const size_t pixel = sb.pixelOfSlot(s);
            if (pixel == SIZE_MAX || !sb.hit[s]) continue;
            const PixelTies ties{accel, sb, s, facingCache, exactDecisions};
            if (classifyAreaPixel(al, glm::dvec3(sb.lsPoint(s)), glm::dvec3(sb.lsNormal(s)),
                                  &ties) != AreaSkip::None)
                continue;
            const AreaPixel px = prepareAreaPixel(al, sb.lsPoint(s), sb.lsNormal(s));
            const ReplicaSeeds seeds =
                replicaSeeds(areaPixelSeed(sampling.seed, 0, uint32_t(pixel)));
            const glm::vec3 org = sb.lsRayOrigin(s);
            for (int round = 0; round < (spp + 15) / 16; ++round) {
                AreaBatch b;
                sampleRound(al, px, seeds, uint32_t(round * kPointsPerRound), b);
                Packet p;
                std::memset(&p, 0, sizeof p);
                p.pixel = uint32_t(pixel);
                for (int k = 0; k < 16; ++k) {
                    p.valid[k] = b.weight[k] > 0.0f ? -1 : 0;
                    p.weight[k] = b.weight[k];
                    p.ray.org_x[k] = org.x, p.ray.org_y[k] = org.y, p.ray.org_z[k] = org.z;
                    p.ray.dir_x[k] = b.dirX[k], p.ray.dir_y[k] = b.dirY[k],
                    p.ray.dir_z[k] = b.dirZ[k];
                    p.ray.tfar[k] = b.tfar[k];
                    p.ray.mask[k] = 0xFFFFFFFFu;
                }
                packets.push_back(p);
            }
        }
        std::vector<Packet> work;
        auto runPlain = [&] {
            forEachWithContext(
                arena, work.size(), 64, true, [&](RTCIntersectContext& ctx, size_t i) {
                    rtcOccluded16(work[i].valid, plain.rtcScene(), &ctx, &work[i].ray);
                });
        };
        std::vector<double> tO, tF, tP, ratio, ratioFar, share;
        for (int r = 0; r < reps; ++r) {
            tO.push_back(timeOnce(runOracle));
            tF.push_back(timeOnce(runOracleFar));
            work = packets;  // outside the timing: Embree overwrites tfar
            tP.push_back(timeOnce(runPlain));
            ratio.push_back(tP.back() / tO.back());
            ratioFar.push_back(tP.back() / tF.back());
            share.push_back(1.0 - tF.back() / tO.back());
        }
        // The plain loop's hits, through the same estimator, give the oracle's V.
        uint64_t rays = 0;
        std::vector<ReplicaSums> sums(n);
        for (const Packet& p : work) {
            addRound(sums[p.pixel], p.weight, p.valid, p.ray.tfar);
            for (int k = 0; k < 16; ++k) rays += p.valid[k] != 0;
        }
        size_t mismatches = 0;
        for (size_t i = 0; i < n; ++i)
            if (S[i] > 0.0f && float(replicaEstimate(sums[i]).V) != V[i]) ++mismatches;
        const double mO = double(st.raysTraced) / median(tO) / 1e6,
                     mP = double(rays) / median(tP) / 1e6;
        std::printf("light %-6s %llu rays (%.1f%% occluded)\n", light.name.c_str(),
                    (unsigned long long)st.raysTraced,
                    100.0 * double(st.raysOccluded) / double(std::max<uint64_t>(1, st.raysTraced)));
        std::printf("  oracle        %7.2f Mrays/s\n", mO);
        std::printf(
            "  rtcOccluded16 %7.2f Mrays/s   oracle / occluded16 = %.2f (median of per-run ratios; "
            "target >= 0.85)\n",
            mP, median(ratio));
        std::printf(
            "  without the near fields:   oracle / occluded16 = %.2f (their share of the oracle's "
            "time: %.1f%%)\n",
            median(ratioFar), 100.0 * median(share));
        std::printf(
            "  near field: %llu pixels with triangles their segments may reach, %llu rays "
            "decided in double there, %llu of them blocked\n",
            (unsigned long long)st.nearFieldPixels, (unsigned long long)st.nearFieldRays,
            (unsigned long long)st.nearFieldOccluded);
        std::printf(
            "  pixels whose V the origin filter changes: %zu; same rays: %s (%llu vs %llu)\n",
            mismatches, rays == st.raysTraced ? "yes" : "NO", (unsigned long long)rays,
            (unsigned long long)st.raysTraced);
        failures += rays != st.raysTraced;
    }

    if (noAdaptive) return failures == 0 ? 0 : 1;
    // Adaptive against uniform at the same worst-pixel half-width, on a smaller image.
    Scene small = makeBenchScene(256, adaptiveSize);
    small.effects = {"penumbra"};
    small.lights = {benchLights()[0]};
    // Both runs sampled: --penumbra auto, the default, may answer the light exactly (a fixed
    // count's estimate makes sampling look dear), and an exact run traces no rays to compare.
    OracleOptions o;
    o.penumbra.method = PenumbraMethod::Sampled;
    OracleResult adaptive = runOracle(small, o);
    const AreaShadowStats& la = *adaptive.stats.lights[0].area;
    o.area.fixedSpp = int(la.sppMax);
    OracleResult uniform = runOracle(small, o);
    const AreaShadowStats& lu = *uniform.stats.lights[0].area;
    std::printf("adaptive vs uniform (rect light, %dx%d, target 0.01):\n", adaptiveSize,
                adaptiveSize);
    std::printf(
        "  adaptive  %12llu rays, mean %.0f spp, max %llu spp, worst half-width %.4f, %.2f s\n",
        (unsigned long long)la.raysTraced, la.sppMean(), (unsigned long long)la.sppMax,
        la.worstHalfWidth, la.seconds);
    std::printf("  uniform   %12llu rays at %d spp, worst half-width %.4f, %.2f s\n",
                (unsigned long long)lu.raysTraced, o.area.fixedSpp, lu.worstHalfWidth, lu.seconds);
    std::printf("  uniform / adaptive rays = %.2f\n",
                double(lu.raysTraced) / double(la.raysTraced));
    return failures ? 1 : 0;
}
