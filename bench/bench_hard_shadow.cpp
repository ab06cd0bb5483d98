// Hard-shadow throughput of the oracle against plain Embree loops over the same rays.
//
//   bench_hard_shadow [--size N] [--grid G] [--reps R]
//
// Generates a scene of at least 100k triangles (a bumpy terrain grid plus floating spheres),
// traces the primary rays once, then for each light times, median of R repetitions:
//   oracle   traceHardShadows (ray setup from the surface buffer, cone and facing tests, 16-wide
//            packets over 4x4 tiles, writing V and cos)
//   occ1     rtcOccluded1 over the same rays, prepared beforehand
//   occ16    rtcOccluded16 over the same rays in the same 4x4-tile packets, prepared beforehand
// The two baselines trace a plain Embree scene (no filter), so the oracle's price includes its
// origin-triangle filter (accel.h); the rays whose answer that filter changes are counted (they
// are the self-intersections a bare loop with the oracle's tiny offset would get). Not a test: it
// prints figures.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <glm/geometric.hpp>

#include <CLI/CLI.hpp>

#include "bench_scene.h"
#include "bench_util.h"
#include "core/camera.h"
#include "core/lights/make_light.h"
#include "oracle/accel.h"
#include "oracle/hard_shadow.h"
#include "oracle/surface_buffer.h"

using namespace so;
using namespace so::bench;

namespace {}  // namespace

int main(int argc, char** argv) {
    int size = 1024, grid = 256, reps = 7;
    CLI::App app{"hard-shadow rays: the oracle against plain Embree loops over the same rays"};
    app.add_option("--size", size, "image side")->check(CLI::Range(16, 8192));
    app.add_option("--grid", grid, "terrain grid cells per side (2 grid^2 triangles)")
        ->check(CLI::Range(8, 4096));
    app.add_option("--reps", reps, "repetitions (median reported)")->check(CLI::Range(1, 100));
    bool noNearField = false;
    app.add_flag("--no-near-field", noNearField,
                 "leave the near fields out (their price: the oracle's time with and without)");
    CLI11_PARSE(app, argc, argv);
    Scene scene = makeBenchScene(grid, size);
    scene.lights.push_back(pointLight("point", {2, 14, 3}));
    scene.lights.push_back(directionalLight("sun", glm::normalize(glm::dvec3(0.5, -1, 0.3))));

    const int threads = int(std::thread::hardware_concurrency());
    std::printf("scene: %zu triangles, %dx%d pixels, %d threads, Embree %s, median of %d runs\n",
                scene.stats.triangles, size, size, threads, EmbreeDevice::version().c_str(), reps);
    EmbreeDevice device("threads=0");
    Accel accel(scene, device);
    Accel plain(scene, device, /*originFilter=*/false);
    Camera camera(scene.camera);
    tbb::task_arena arena(threads);
    SurfaceBuffer sb;
    arena.execute([&] { sb = tracePrimary(accel, camera, nullptr); });
    buildNearFieldsTimed(arena, accel, sb, noNearField);

    const size_t n = size_t(sb.width) * size_t(sb.height);
    std::vector<float> V(n), C(n);
    for (const Light& light : scene.lights) {
        HardLight hl = makeHardLight(light, accel.frame());
        HardShadowStats st;
        auto runOracle = [&] {
            arena.execute([&] {
                st = traceHardShadows(accel, sb, hl, {V.data(), C.data(), nullptr}, nullptr);
            });
        };
        // The same pass on the scene without the origin filter: the filter's share of the time.
        std::vector<float> Vplain(n), Cplain(n);
        auto runOraclePlain = [&] {
            arena.execute([&] {
                traceHardShadows(plain, sb, hl, {Vplain.data(), Cplain.data(), nullptr}, nullptr);
            });
        };

        // The same pass without the near fields (moved aside for the run): their share of the time.
        NearFields aside;
        auto runOracleFar = [&] {
            std::swap(aside, sb.nearFields);
            arena.execute([&] {
                traceHardShadows(accel, sb, hl, {Vplain.data(), Cplain.data(), nullptr}, nullptr);
            });
            std::swap(aside, sb.nearFields);
        };
        // The same rays, prepared outside the timing: packets in the oracle's 4x4-tile order.
        const int tilesX = (sb.width + 3) / 4, tilesY = (sb.height + 3) / 4;
        std::vector<RTCRay16> packets(size_t(tilesX) * size_t(tilesY));
        // Embree reads the valid mask with aligned vector loads.
        struct alignas(64) Valid16 {
            int v[16];
            int& operator[](int k) { return v[k]; }
            int* data() { return v; }
        };
        std::vector<Valid16> valid(packets.size());
        std::vector<RTCRay> singles;
        std::vector<size_t> singlePixel;
        for (int ty = 0; ty < tilesY; ++ty)
            for (int tx = 0; tx < tilesX; ++tx) {
                size_t p = size_t(ty) * size_t(tilesX) + size_t(tx);
                RTCRay16& r = packets[p];
                std::memset(&r, 0, sizeof r);
                for (int k = 0; k < 16; ++k) {
                    valid[p][k] = 0;
                    int x = tx * 4 + (k & 3), y = ty * 4 + (k >> 2);
                    if (x >= sb.width || y >= sb.height) continue;
                    size_t i = size_t(y) * size_t(sb.width) + size_t(x);
                    ShadowRaySetup s = setupShadowRay(accel, sb, sb.slot(x, y), hl);
                    if (s.kind != ShadowRayKind::Traced) continue;
                    valid[p][k] = -1;
                    r.org_x[k] = s.org.x, r.org_y[k] = s.org.y, r.org_z[k] = s.org.z;
                    r.dir_x[k] = s.dir.x, r.dir_y[k] = s.dir.y, r.dir_z[k] = s.dir.z;
                    r.tnear[k] = 0.0f, r.tfar[k] = s.tfar, r.mask[k] = 0xFFFFFFFFu;
                    RTCRay one{};
                    one.org_x = s.org.x, one.org_y = s.org.y, one.org_z = s.org.z;
                    one.dir_x = s.dir.x, one.dir_y = s.dir.y, one.dir_z = s.dir.z;
                    one.tnear = 0.0f, one.tfar = s.tfar, one.mask = 0xFFFFFFFFu;
                    singles.push_back(one);
                    singlePixel.push_back(i);
                }
            }
        const size_t rays = singles.size();

        std::vector<RTCRay> work1;
        std::vector<RTCRay16> work16;
        // Each timed loop starts from a fresh copy of its rays (Embree overwrites tfar), made
        // outside the timing.
        auto runOcc1 = [&] {
            forEachWithContext(arena, rays, 1024, false, [&](RTCIntersectContext& ctx, size_t i) {
                rtcOccluded1(plain.rtcScene(), &ctx, &work1[i]);
            });
        };
        auto runOcc16 = [&] {
            forEachWithContext(
                arena, work16.size(), 64, true, [&](RTCIntersectContext& ctx, size_t p) {
                    bool any = false;
                    for (int k = 0; k < 16; ++k) any |= valid[p][k] != 0;
                    if (any) rtcOccluded16(valid[p].data(), plain.rtcScene(), &ctx, &work16[p]);
                });
        };
        // Interleaved, so that whatever else the machine does falls on all three alike; the ratio
        // is taken per repetition and its median reported.
        std::vector<double> tO, tOF, tOP, t1s, t16s, r1, r16, rFar, rPlain, share;
        for (int r = 0; r < reps; ++r) {
            tO.push_back(timeOnce(runOracle));
            tOF.push_back(timeOnce(runOracleFar));
            tOP.push_back(timeOnce(runOraclePlain));
            work1 = singles;
            t1s.push_back(timeOnce(runOcc1));
            work16 = packets;
            t16s.push_back(timeOnce(runOcc16));
            r1.push_back(t1s.back() / tO.back());
            r16.push_back(t16s.back() / tO.back());
            rFar.push_back(t16s.back() / tOF.back());
            rPlain.push_back(t16s.back() / tOP.back());
            share.push_back(1.0 - tOF.back() / tO.back());
        }
        const double tOracle = median(tO), t1 = median(t1s), t16 = median(t16s);
        // The oracle's own work without tracing: setting up every packet's rays.
        std::vector<double> tSetup;
        std::vector<float> sink(size_t(tilesX) * size_t(tilesY));
        for (int rep = 0; rep < reps; ++rep)
            tSetup.push_back(timeOnce([&] {
                arena.execute([&] {
                    tbb::parallel_for(tbb::blocked_range<size_t>(0, sink.size(), 64),
                                      [&](const tbb::blocked_range<size_t>& r) {
                                          PacketSetup ps;
                                          for (size_t t = r.begin(); t != r.end(); ++t) {
                                              setupPacket(accel, sb, t * 16, hl, ps);
                                              sink[t] = ps.tfar[0] + ps.cosine[15];
                                          }
                                      });
                });
            }));
        std::printf(
            "  setup only: %.2f ms, oracle %.2f ms (without the origin filter %.2f ms), "
            "occluded16 %.2f ms\n",
            1e3 * median(tSetup), 1e3 * tOracle, 1e3 * median(tOP), 1e3 * t16);
        runOracle();

        // Same rays; answers differ only where the origin filter rejected a self-intersection.
        size_t mismatch1 = 0, mismatch16 = 0;
        for (size_t j = 0; j < rays; ++j)
            mismatch1 += (work1[j].tfar >= 0.0f) != (V[singlePixel[j]] == 1.0f);
        for (int ty = 0; ty < tilesY; ++ty)
            for (int tx = 0; tx < tilesX; ++tx) {
                size_t p = size_t(ty) * size_t(tilesX) + size_t(tx);
                for (int k = 0; k < 16; ++k) {
                    if (!valid[p][k]) continue;
                    size_t i =
                        size_t(ty * 4 + (k >> 2)) * size_t(sb.width) + size_t(tx * 4 + (k & 3));
                    mismatch16 += (work16[p].tfar[k] >= 0.0f) != (V[i] == 1.0f);
                }
            }
        double mOracle = double(st.raysTraced) / tOracle / 1e6, m1 = double(rays) / t1 / 1e6,
               m16 = double(rays) / t16 / 1e6;
        std::printf("light %-6s %zu rays (%.1f%% occluded)\n", light.name.c_str(), rays,
                    100.0 * double(st.raysOccluded) / double(std::max<uint64_t>(1, st.raysTraced)));
        std::printf("  oracle        %7.2f Mrays/s\n", mOracle);
        std::printf(
            "  rtcOccluded1  %7.2f Mrays/s   oracle / occluded1  = %.2f (median of per-run "
            "ratios)\n",
            m1, median(r1));
        std::printf(
            "  rtcOccluded16 %7.2f Mrays/s   oracle / occluded16 = %.2f (median of per-run ratios; "
            "target >= 0.85)\n",
            m16, median(r16));
        std::printf(
            "  without the near fields:   oracle / occluded16 = %.2f (their share of the "
            "oracle's time: %.1f%%)\n",
            median(rFar), 100.0 * median(share));
        std::printf("  without the origin filter: oracle / occluded16 = %.2f\n", median(rPlain));
        std::printf(
            "  answers changed by the origin filter: %zu (occluded1), %zu (occluded16) of %zu\n",
            mismatch1, mismatch16, rays);
        std::printf(
            "  near field: %llu rays decided in double (their segment may reach a near "
            "triangle), %llu of them blocked there\n",
            (unsigned long long)st.nearFieldPixels, (unsigned long long)st.nearFieldOccluded);
        if (st.raysTraced != rays) return 1;
    }
    return 0;
}
