// The cost model of `--penumbra auto` (oracle/penumbra_choice.cpp), fitted from counted work and
// measured processor time (docs/benchmarks.md, "The cost model of --penumbra auto";
// scripts/penumbra-calibration runs it on every shipped and real scene in one command).
//
// Per area light of each scene: the sampled pass to the target and the exact pass (finding its
// own pixels) on every point the camera hit, each on one thread, timed by that thread's processor
// clock (CLOCK_THREAD_CPUTIME_ID: on a loaded machine it counts this work, not the other
// processes'), repeated, the median kept. Their counts (the sampled pass's rays; the exact pass's
// points, BVH candidates, occluders and bound sides) are the ones the probe counts. Then:
// - the fit: the sampled pass's seconds per ray and per point, and the exact pass's per point,
//   candidate, occluder and bound side, by least squares on relative residuals (each light counts
//   the same whatever its size), non-negative (every subset of the terms is tried, the best with
//   non-negative constants kept), each light's residual printed;
// - what auto chose (a whole oracle run, one thread, with the constants compiled in), its
//   estimates of both costs against the measured ones, and whether the cheaper measured method
//   was the one it chose.
//
//   bench_penumbra_cost [--width W] [--height H] [--target T] [--repeats R] [--bunny] SCENE...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bunny_scene.h"
#include "core/camera.h"
#include "core/scene.h"
#include "embree/embree_handles.h"
#include "oracle/accel.h"
#include "oracle/area_light.h"
#include "oracle/area_shadow.h"
#include "oracle/exact_penumbra.h"
#include "oracle/exact_scene.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/mesh_facing.h"
#include "oracle/near_field.h"
#include "oracle/oracle.h"
#include "oracle/surface_buffer.h"
#include "oracle/thread_arena.h"

using namespace so;

namespace {

double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// One light's counted work and measured processor seconds.
struct Row {
    std::string name;
    bool bounded = false;  // disk or sphere
    double points = 0, rays = 0, candidates = 0, occluders = 0, sides = 0, kept = 0;
    double triangles = 0, alphaTests = 0;  // the scene's; the sampled pass's
    double sampledSeconds = 0, exactSeconds = 0;
    double sampledSpread = 0, exactSpread = 0;  // (max - min) / median over the repeats
    // auto's choice in a whole run with the compiled constants, and its estimates.
    std::string chosen;
    double estExact = 0, estSampled = 0;
};

// The scene's camera image at one thread: what both passes read.
struct Setup {
    Setup(const Scene& scene)
        : accel(scene, device), threads(1), exact(scene, accel.frame()), camera(scene.camera) {
        threads.arena().execute([&] {
            sb = tracePrimary(accel, camera, nullptr);
            buildNearFields(accel, sb);
        });
        facing = meshFacing(exact, accel.frame().lsFromWs(camera.wsEye()));
        for (size_t s = 0; s < sb.slotCount(); ++s)
            points += sb.pixelOfSlot(s) != SIZE_MAX && sb.hit[s];
    }
    EmbreeDevice device{"threads=0"};
    Accel accel;
    ThreadArena threads;
    ExactScene exact;
    Camera camera;
    SurfaceBuffer sb;
    MeshFacing facing;
    double points = 0;
};

double spread(const std::vector<double>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return (*hi - *lo) / std::max(median(v), 1e-12);
}

// Both passes on every point of `s`, `repeats` times each.
Row measure(const Scene& scene, const Setup& s, uint32_t li, double target, int repeats) {
    const Light& light = scene.lights[li];
    const AreaLight al = makeAreaLight(light, s.accel.frame());
    const size_t pixels = size_t(s.sb.width) * size_t(s.sb.height);
    std::vector<float> V(pixels), se(pixels), spp(pixels), cosine(pixels), mask(pixels),
        bound(pixels);
    AreaSampling sampling;
    sampling.targetError = target;
    ExactPenumbraOptions options;
    options.method = PenumbraMethod::Exact;
    Row r;
    r.name = scene.path.stem().stem().string() + " " + light.name + " (" +
             lightTypeName(light.type) + ")";
    r.bounded = areaLightKind(light.type).bounded();
    r.points = s.points;
    r.triangles = double(scene.stats.triangles);
    std::vector<double> ts, te;
    tbb::task_arena& arena = const_cast<ThreadArena&>(s.threads).arena();
    for (int k = 0; k < repeats; ++k) {
        arena.execute([&] {
            double t0 = threadSeconds();
            const AreaShadowStats a =
                traceAreaShadows(s.accel, s.sb, al, sampling, li,
                                 {V.data(), se.data(), spp.data(), cosine.data()}, nullptr);
            ts.push_back(threadSeconds() - t0);
            r.rays = double(a.raysTraced);
            r.alphaTests = double(a.alphaTests);
            ExactPenumbraPlanes e;
            e.V = V.data();
            e.stderr_ = se.data();
            e.cosine = cosine.data();
            e.exactMask = mask.data();
            e.bound = r.bounded ? bound.data() : nullptr;
            std::vector<uint8_t> needsSampling;
            e.needsSampling = &needsSampling;
            t0 = threadSeconds();
            const ExactPenumbraStats x =
                exactPenumbraPass(s.exact, s.sb, al, options, e, nullptr, &s.facing);
            te.push_back(threadSeconds() - t0);
            r.candidates = double(x.candidatesTotal);
            r.occluders = double(x.occludersTotal);
            r.sides = double(x.boundSidesTotal);
            r.kept = double(x.pixelsTooManyOccluders + x.pixelsAlphaTested);
        });
    }
    r.sampledSeconds = median(ts);
    r.exactSeconds = median(te);
    r.sampledSpread = spread(ts);
    r.exactSpread = spread(te);
    return r;
}

// auto's choices in a whole oracle run (one thread), with the constants compiled in.
void autoChoices(const Scene& scene, double target, std::vector<Row>& rows, size_t first) {
    OracleOptions o;
    o.threads = 1;
    o.area.targetError = target;
    o.penumbra.method = PenumbraMethod::Auto;
    const OracleResult result = runOracle(scene, o);
    size_t k = first;
    for (const OracleLightStats& l : result.stats.lights) {
        if (!l.choice || k >= rows.size()) continue;
        rows[k].chosen = penumbraMethodName(l.choice->chosen);
        rows[k].estExact = l.choice->exactSeconds;
        rows[k].estSampled = l.choice->sampledSeconds;
        ++k;
    }
}

// Least squares of y ~ X c on relative residuals, c >= 0: every subset of the columns is tried
// (at most 4 here), the best fit with every constant non-negative kept.
std::vector<double> fitNonNegative(const std::vector<std::vector<double>>& X,
                                   const std::vector<double>& y) {
    const size_t m = X.empty() ? 0 : X[0].size();
    std::vector<double> best(m, 0.0);
    double bestError = INFINITY;
    for (unsigned subset = 1; subset < (1u << m); ++subset) {
        std::vector<size_t> cols;
        for (size_t j = 0; j < m; ++j)
            if (subset & (1u << j)) cols.push_back(j);
        const size_t q = cols.size();
        // Normal equations of the rows divided by y (relative residuals), Gaussian elimination.
        std::vector<std::vector<double>> A(q, std::vector<double>(q + 1, 0.0));
        for (size_t i = 0; i < y.size(); ++i)
            for (size_t a = 0; a < q; ++a) {
                for (size_t b = 0; b < q; ++b)
                    A[a][b] += X[i][cols[a]] * X[i][cols[b]] / (y[i] * y[i]);
                A[a][q] += X[i][cols[a]] / y[i];
            }
        bool singular = false;
        for (size_t a = 0; a < q && !singular; ++a) {
            size_t pivot = a;
            for (size_t b = a + 1; b < q; ++b)
                if (std::fabs(A[b][a]) > std::fabs(A[pivot][a])) pivot = b;
            std::swap(A[a], A[pivot]);
            if (std::fabs(A[a][a]) < 1e-300) singular = true;
            for (size_t b = 0; b < q && !singular; ++b) {
                if (b == a) continue;
                const double f = A[b][a] / A[a][a];
                for (size_t c = a; c <= q; ++c) A[b][c] -= f * A[a][c];
            }
        }
        if (singular) continue;
        std::vector<double> c(m, 0.0);
        bool negative = false;
        for (size_t a = 0; a < q; ++a) {
            c[cols[a]] = A[a][q] / A[a][a];
            negative |= c[cols[a]] < 0.0;
        }
        if (negative) continue;
        double error = 0.0;
        for (size_t i = 0; i < y.size(); ++i) {
            double model = 0.0;
            for (size_t j = 0; j < m; ++j) model += X[i][j] * c[j];
            error += (model / y[i] - 1.0) * (model / y[i] - 1.0);
        }
        if (error < bestError) bestError = error, best = c;
    }
    return best;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0.0;
    for (size_t j = 0; j < a.size(); ++j) s += a[j] * b[j];
    return s;
}

void report(const std::vector<Row>& rows) {
    std::vector<std::vector<double>> Xs, Xe;
    std::vector<double> ys, ye;
    for (const Row& r : rows) {
        Xs.push_back({r.rays, r.rays * std::log2(std::max(r.triangles, 2.0)), r.alphaTests});
        ys.push_back(r.sampledSeconds);
        Xe.push_back({r.points, r.candidates, r.occluders, r.sides});
        ye.push_back(r.exactSeconds);
    }
    const std::vector<double> cs = fitNonNegative(Xs, ys), ce = fitNonNegative(Xe, ye);
    std::printf(
        "\nfit (processor seconds, one thread, relative least squares, non-negative):\n"
        "  sampled: %.3g s per ray + %.3g s per ray and log2(triangles) + %.3g s per alpha "
        "test\n"
        "  exact:   %.3g s per point + %.3g s per candidate + %.3g s per occluder + "
        "%.3g s per bound side\n",
        cs[0], cs[1], cs[2], ce[0], ce[1], ce[2], ce[3]);
    std::printf("\n%-36s %8s %7s %9s %9s %9s %10s | %9s %6s %9s %6s | %8s %8s | %-7s %9s %9s %s\n",
                "light", "tri.", "points", "rays", "cand.", "occl.", "sides", "sampled s", "fit",
                "exact s", "fit", "spread s", "spread e", "auto", "est. s", "est. e", "right?");
    double worstS = 0, worstE = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
        const Row& r = rows[i];
        const double fs = dot(Xs[i], cs) / ys[i] - 1.0, fe = dot(Xe[i], ce) / ye[i] - 1.0;
        worstS = std::max(worstS, std::fabs(fs));
        worstE = std::max(worstE, std::fabs(fe));
        const bool exactCheaper = r.exactSeconds <= r.sampledSeconds;
        const double ratio = std::max(r.exactSeconds, r.sampledSeconds) /
                             std::max(std::min(r.exactSeconds, r.sampledSeconds), 1e-12);
        char verdict[64] = "-";
        if (!r.chosen.empty())
            std::snprintf(verdict, sizeof verdict, "%s (measured %s cheaper, x%.2f)",
                          (r.chosen == "exact") == exactCheaper ? "yes" : "no",
                          exactCheaper ? "exact" : "sampled", ratio);
        std::printf(
            "%-36s %8.0f %7.0f %9.3g %9.3g %9.3g %10.3g | %9.4f %+5.0f%% %9.4f %+5.0f%% | %7.0f%% "
            "%7.0f%% | %-7s %9.4f %9.4f %s\n",
            r.name.c_str(), r.triangles, r.points, r.rays, r.candidates, r.occluders, r.sides,
            r.sampledSeconds, 100 * fs, r.exactSeconds, 100 * fe, 100 * r.sampledSpread,
            100 * r.exactSpread, r.chosen.c_str(), r.estSampled, r.estExact, verdict);
    }
    std::printf("largest |residual|: sampled %.0f%%, exact %.0f%%\n", 100 * worstS, 100 * worstE);
}

}  // namespace

int main(int argc, char** argv) {
    int width = 96, height = 72, repeats = 3;
    double target = 0.01;
    bool bunny = false;
    std::vector<std::string> paths;
    CLI::App app{"the cost model of --penumbra auto: counted work against processor time"};
    app.add_option("--width", width, "image width")->check(CLI::Range(8, 2048));
    app.add_option("--height", height, "image height")->check(CLI::Range(8, 2048));
    app.add_option("--target", target, "the sampled pass's 95% half-width")
        ->check(CLI::Range(1e-4, 0.1));
    app.add_option("--repeats", repeats, "runs of each pass (the median is kept)")
        ->check(CLI::Range(1, 99));
    app.add_flag("--bunny", bunny, "also the CGAL bunny under a low rect light");
    app.add_option("scenes", paths, "scene files");
    CLI11_PARSE(app, argc, argv);
    std::vector<Scene> scenes;
    for (const std::string& p : paths) scenes.push_back(loadScene(p));
    if (bunny) {
        std::string why;
        if (const MeshPrimitive* mesh = test::cgalBunny(why)) {
            scenes.push_back(test::makeBunnyScene(*mesh, width, height));
            test::useLowRectLight(scenes.back());
            scenes.back().path = "bunny.scene.json";
        } else {
            std::printf("bunny: skipped (%s)\n", why.c_str());
        }
    }
    std::vector<Row> rows;
    for (Scene& scene : scenes) {
        if (!scene.hasEffect("penumbra")) continue;
        scene.camera.width = width;
        scene.camera.height = height;
        const Setup setup(scene);
        const size_t first = rows.size();
        for (uint32_t li = 0; li < scene.lights.size(); ++li) {
            const std::string kind = lightTypeName(scene.lights[li].type);
            if (kind != "rect" && kind != "disk" && kind != "sphere") continue;
            rows.push_back(measure(scene, setup, li, target, repeats));
            std::fprintf(stderr, "%s: sampled %.4f s, exact %.4f s\n", rows.back().name.c_str(),
                         rows.back().sampledSeconds, rows.back().exactSeconds);
        }
        autoChoices(scene, target, rows, first);
    }
    report(rows);
    return 0;
}
