// What the exact penumbra pass costs (docs/benchmarks.md, "Exact penumbrae against RQMC"):
//
// 1. Growth: the closed-form scene (tests/support/test_scenes.h PenumbraScene) with its square
// occluder
//    split into k x k squares, 2k^2 triangles tiling the same square, so that V and its closed
//    form stay the same while the triangles in each pixel's pyramid grow as k^2. Per k: the exact
//    pass's seconds per pixel as it ships and as the plain union (two curves), occluders per
//    pixel (mean, p99 bound, max), the largest |V - closed form| over its pixels, and RQMC's
//    seconds per penumbra pixel at a stated 0.001 on the same scene; then the fitted growth of
//    the time per pixel with the occluders, for each curve.
// 2. RQMC at stated half-widths 0.01, 0.001 and 0.0001 (max spp 2^20) against the exact pass on
//    the shipped penumbra_square (200 x 200; its exact pass matches the closed form, part 1) and
//    two scenes without a closed form: soft_chair's window (its sphere bulb left out: it has no
//    exact pass) and the CGAL bunny under a low rect light. Each RQMC run's realised penumbra error
//    and its intervals' coverage are measured against the exact pass over every pixel (which
//    finds its own pixels), run as it ships and as a plain union (no shortcuts, every back face),
//    and what `auto` chooses at 0.01.
//
//   bench_exact_penumbra [--size N] [--max-k K] [--bunny-size W] [--tightest T]
//   bench_exact_penumbra --exact-only N [--bunny-size W]   (the bunny's exact run alone, N times)
//   bench_exact_penumbra --light-kinds N [--repeats R]   (rect, disk and sphere on one geometry)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include "bunny_scene.h"
#include "core/channels.h"
#include "core/lights/make_light.h"
#include "core/local_frame.h"
#include "core/scene.h"
#include "exact_penumbra_util.h"
#include "lambert.h"
#include "oracle/area_shadow.h"
#include "oracle/offset.h"
#include "oracle/oracle.h"
#include "oracle/polygon_visibility.h"
#include "test_scenes.h"

using namespace so;

namespace {

// The closed-form scene with its occluder as k x k squares.
Scene tiledPenumbraScene(int size, int k) {
    test::PenumbraScene s = test::makePenumbraScene(size, size);
    const test::AxisRect& o = s.occluder;
    s.scene.meshes[1] = test::makeGrid({0.5 * (o.x0 + o.x1), o.y, 0.5 * (o.z0 + o.z1)},
                                       {o.x1 - o.x0, 0, 0}, {0, 0, -(o.z1 - o.z0)}, k, "occluder");
    finalizeScene(s.scene);
    return s.scene;
}

// plain: the exact pass without its shortcuts, with every back face in the union and no merging
// (issue 45's "before", on the pass's own pixels).
// cpu: the whole run's processor seconds, all threads (std::clock): on a loaded machine the work,
// where wall seconds measure the other processes too.
OracleResult run(const Scene& scene, double target, PenumbraMethod method, bool plain = false,
                 double* cpu = nullptr) {
    const std::clock_t c0 = std::clock();
    OracleOptions o;
    o.area.targetError = target;
    o.area.maxSpp = 1 << 20;
    o.penumbra.method = method;
    o.penumbra.shortcuts = o.penumbra.backFaces = o.penumbra.merge = !plain;
    OracleResult r = runOracle(scene, o);
    if (cpu) *cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    return r;
}

double meanOccluders(const ExactPenumbraStats& e) {
    return double(e.occludersTotal) / double(std::max<uint64_t>(e.pixelsExact, 1));
}

// The largest |V - closed form| over the pixels the exact pass gave.
double maxClosedFormError(const ChannelImage& img, const std::string& light) {
    namespace ch = channels;
    const test::PenumbraScene ref;
    const float* V = img.channel(light + ".V");
    const float* exact = img.channel(light + "." + ch::kExact);
    double worst = 0.0;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (exact[i] != 1.0f) continue;
        const glm::dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i],
                           img.channel(ch::kPZ)[i]);
        const glm::dvec3 n(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i],
                           img.channel(ch::kNZ)[i]);
        const double v = test::exactRectLightRectOccluderV(p, n, ref.light, ref.occluder);
        worst = std::max(worst, std::fabs(double(V[i]) - v));
    }
    return worst;
}

// The least-squares slope of log y against log x.
double logLogSlope(const std::vector<std::pair<double, double>>& xy) {
    double mx = 0, my = 0;
    for (const auto& [x, y] : xy) mx += std::log(x), my += std::log(y);
    mx /= double(xy.size()), my /= double(xy.size());
    double sxy = 0, sxx = 0;
    for (const auto& [x, y] : xy)
        sxy += (std::log(x) - mx) * (std::log(y) - my),
            sxx += (std::log(x) - mx) * (std::log(x) - mx);
    return sxy / sxx;
}

// Per k, the pass as it ships ("fast") and the plain union of issue 31 ("plain": no shortcuts,
// every back face, each triangle clipped, no merging), both over every pixel; the occluders per
// pixel are the plain union's (the triangles whose clipped shadow reaches the light: what the
// pyramid holds), the x of both curves.
void growth(int size, int maxK) {
    std::printf(
        "growth: the closed-form scene at %dx%d, its occluder as k x k squares\n"
        "%6s %9s %8s %10s %9s %8s %11s %12s %11s %12s %14s %12s\n",
        size, size, "k", "triangles", "pixels", "occ. mean", "p99 <=", "max", "exact s",
        "exact us/px", "plain s", "plain us/px", "max |V - cf|", "RQMC us/px");
    std::vector<std::pair<double, double>> fitFast, fitPlain;  // (occluders, us per pixel)
    for (int k = 1; k <= maxK; k *= 2) {
        const Scene scene = tiledPenumbraScene(size, k);
        const OracleResult ex = run(scene, 0.01, PenumbraMethod::Exact);
        const ExactPenumbraStats& e = *ex.stats.lights[0].area->exact;
        const OracleResult pl = run(scene, 0.01, PenumbraMethod::Exact, true);
        const ExactPenumbraStats& p = *pl.stats.lights[0].area->exact;
        const OracleResult rq = run(scene, 0.001, PenumbraMethod::Sampled);
        const AreaShadowStats& ra = *rq.stats.lights[0].area;
        const uint64_t rqPenumbra = ra.pixelsSampled - ra.pixelsAgreeing;
        const double usFast = 1e6 * e.seconds / double(std::max<uint64_t>(e.pixelsExact, 1));
        const double usPlain = 1e6 * p.seconds / double(std::max<uint64_t>(p.pixelsExact, 1));
        std::printf(
            "%6d %9llu %8llu %10.1f %9llu %8llu %11.3f %12.1f %11.3f %12.1f %14.2e %12.1f\n", k,
            (unsigned long long)scene.stats.triangles, (unsigned long long)p.pixelsExact,
            meanOccluders(p), (unsigned long long)occluderQuantileBound(p.occluders, 0.99),
            (unsigned long long)p.occludersMax, e.seconds, usFast, p.seconds, usPlain,
            std::max(maxClosedFormError(ex.image, scene.lights[0].name),
                     maxClosedFormError(pl.image, scene.lights[0].name)),
            1e6 * ra.seconds / double(std::max<uint64_t>(rqPenumbra, 1)));
        std::fflush(stdout);
        if (meanOccluders(p) >= 8.0) {
            fitFast.emplace_back(meanOccluders(p), usFast);
            fitPlain.emplace_back(meanOccluders(p), usPlain);
        }
    }
    if (fitFast.size() < 2) return;
    std::printf(
        "  time per pixel ~ occluders^%.2f fast, ^%.2f plain (least squares over the %zu rows with "
        "8 or more)\n",
        logLogSlope(fitFast), logLogSlope(fitPlain), fitFast.size());
}

// Realised error of a sampled V against the exact one, over the pixels the exact pass gave with
// 0 < V_exact < 1; and how its stated 95% intervals cover the exact V there.
struct Realised {
    double mae = 0.0, p99 = 0.0;
    size_t pixels = 0;
    size_t covered = 0;     // |V - V_exact| <= the stated half-width
    size_t agreeing = 0;    // the sampled pass's samples all agreed (V 0 or 1): no exact pass
    size_t farOutside = 0;  // sampled, disagreeing, yet beyond 10 stated half-widths
    // Disagreeing pixels outside their interval, and those of them whose sampled V the exact V at
    // the shadow rays' origin (p moved kLsOriginOffset along the normal, offset.h) lies within.
    size_t outside = 0, explainedByOffset = 0;
};

// What the sampled runs are measured against: the exact pass over every pixel, and the exact
// tracer over the scene (world space) for V at the shadow rays' offset origin.
struct Reference {
    const Scene& scene;
    ChannelImage image;  // --penumbra exact --exact-pixels all
    std::vector<ExactTracer::MeshView> views;
    ExactTracer tracer;
    RectLightShape shape;
    double wsOffset;  // the origin offset (offset.h) in world units

    Reference(const Scene& s, ChannelImage exact)
        : scene(s),
          image(std::move(exact)),
          views(meshViews(s)),
          tracer(views),
          shape(test::rectLightShape(s.lights[0])),
          wsOffset(LocalFrame::fit(s.wsBounds).wsLength(kLsOriginOffset)) {}

    static std::vector<ExactTracer::MeshView> meshViews(const Scene& s) {
        std::vector<ExactTracer::MeshView> v;
        for (const MeshPrimitive& m : s.meshes) v.push_back({&m.wsPositions, &m.indices});
        return v;
    }

    // The exact V at the sampled pass's ray origin for pixel i: its P (float) put back on its
    // triangle's plane, moved along the face normal by the origin offset.
    double atRayOrigin(size_t i) const {
        namespace ch = channels;
        const TriangleId id{uint32_t(image.channel(ch::kMeshId)[i]),
                            uint32_t(image.channel(ch::kPrimId)[i])};
        const MeshPrimitive& m = scene.meshes[id.mesh];
        const uint32_t* t = &m.indices[3 * size_t(id.prim)];
        const glm::dvec3 a = m.wsPositions[t[0]], b = m.wsPositions[t[1]], c = m.wsPositions[t[2]];
        glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        if (glm::dot(n, glm::dvec3(image.channel(ch::kNX)[i], image.channel(ch::kNY)[i],
                                   image.channel(ch::kNZ)[i])) < 0.0)
            n = -n;
        glm::dvec3 p(image.channel(ch::kPX)[i], image.channel(ch::kPY)[i],
                     image.channel(ch::kPZ)[i]);
        p -= glm::dot(p - a, n) * n;
        return rectLightVisibility(tracer, shape, p + wsOffset * n, n, id, 1u << 20).V;
    }
};

Realised realisedError(const Reference& ref, const ChannelImage& sampled) {
    const std::string light = ref.scene.lights[0].name;
    const float* Vs = sampled.channel(light + ".V");
    const float* SE = sampled.channel(light + ".stderr");
    const float* Ve = ref.image.channel(light + ".V");
    const float* mask = ref.image.channel(light + "." + channels::kExact);
    std::vector<double> errors;
    Realised r;
    for (size_t i = 0; i < ref.image.pixelCount(); ++i) {
        if (!(mask[i] == 1.0f && Ve[i] > 0.0f && Ve[i] < 1.0f)) continue;
        const double e = std::fabs(double(Vs[i]) - double(Ve[i]));
        const double halfWidth = kIntervalQuantile95 * double(SE[i]);
        errors.push_back(e);
        r.covered += e <= halfWidth;
        r.agreeing += Vs[i] == 0.0f || Vs[i] == 1.0f;
        if (Vs[i] == 0.0f || Vs[i] == 1.0f || e <= halfWidth) continue;
        ++r.outside;
        r.farOutside += e > 10.0 * halfWidth;
        r.explainedByOffset += std::fabs(double(Vs[i]) - ref.atRayOrigin(i)) <= halfWidth;
    }
    r.pixels = errors.size();
    if (errors.empty()) return r;
    for (double e : errors) r.mae += e;
    r.mae /= double(errors.size());
    const size_t q = std::min(errors.size() - 1, size_t(0.99 * double(errors.size())));
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(q), errors.end());
    r.p99 = errors[q];
    return r;
}

// RQMC at three targets and the exact pass on one rect light (the scene's first light).
void againstRqmc(const std::string& name, const Scene& scene, double tightest) {
    const std::string light = scene.lights[0].name;
    std::printf("\n%s (%d x %d, %llu triangles), light \"%s\":\n", name.c_str(), scene.camera.width,
                scene.camera.height, (unsigned long long)scene.stats.triangles, light.c_str());
    double cpuAll = 0.0, cpuPlain = 0.0, cpu = 0.0;
    const OracleResult all = run(scene, 0.01, PenumbraMethod::Exact, false, &cpuAll);
    const OracleResult plain = run(scene, 0.01, PenumbraMethod::Exact, true, &cpuPlain);
    const OracleResult automatic = run(scene, 0.01, PenumbraMethod::Auto);
    const Reference ref(scene, all.image);
    for (double target : {0.01, 0.001, 0.0001}) {
        if (target < tightest) break;
        const OracleResult r = run(scene, target, PenumbraMethod::Sampled, false, &cpu);
        const AreaShadowStats& a = *r.stats.lights[0].area;
        const Realised e = realisedError(ref, r.image);
        std::printf(
            "  RQMC target %-7g %9.3f s (run %.2f cpu s)  spp mean %8.0f  unconverged %6llu  "
            "penumbra mae %.2e  "
            "p99 %.2e  covered %.1f%% of %zu pixels (%zu agreeing, at 0 or 1)\n"
            "    disagreeing and outside: %zu (%zu beyond 10 half-widths); within their interval "
            "of the exact V at the rays' offset origin: %zu\n",
            target, a.seconds, cpu, a.sppMean(), (unsigned long long)a.pixelsUnconverged, e.mae,
            e.p99, 100.0 * double(e.covered) / double(std::max<size_t>(e.pixels, 1)), e.pixels,
            e.agreeing, e.outside, e.farOutside, e.explainedByOffset);
        std::fflush(stdout);
    }
    for (const OracleResult* r : {&plain, &all}) {
        const AreaShadowStats& a = *r->stats.lights[0].area;
        const ExactPenumbraStats& e = *a.exact;
        const Realised err = realisedError(ref, r->image);
        std::printf(
            "  exact, %-6s %9.3f s (run %.2f cpu s; + %.3f s sampled where it gave no answer)  "
            "%llu pixels (lit "
            "%llu, covered %llu without a union), occluders mean %.1f, p99 <= %llu, max %llu; "
            "back faces left out %llu of %llu candidates; kept sampled: %llu; penumbra mae %.2e\n",
            r == &plain ? "plain" : "fast", e.seconds, r == &plain ? cpuPlain : cpuAll, a.seconds,
            (unsigned long long)e.pixelsExact, (unsigned long long)e.pixelsLit,
            (unsigned long long)e.pixelsCovered, meanOccluders(e),
            (unsigned long long)occluderQuantileBound(e.occluders, 0.99),
            (unsigned long long)e.occludersMax, (unsigned long long)e.backFacesTotal,
            (unsigned long long)e.candidatesTotal,
            (unsigned long long)(e.pixelsTooManyOccluders + e.pixelsAlphaTested), err.mae);
    }
    const OracleLightStats& l = automatic.stats.lights[0];
    if (l.choice)
        std::printf(
            "  auto at 0.01: %s (%s; probe %llu points, %llu rays, %llu candidates, %llu "
            "occluders)\n",
            penumbraMethodName(l.choice->chosen), l.choice->reason.c_str(),
            (unsigned long long)l.choice->probePoints, (unsigned long long)l.choice->probeRays,
            (unsigned long long)l.choice->probeCandidates,
            (unsigned long long)l.choice->probeOccluders);
}

// --exact-only: the bunny's exact pass alone, `runs` times, each run's processor seconds and the
// pass's own wall seconds (a profiler then sees nothing else but the scene's set-up).
int exactOnlyRuns(int width, int runs) {
    std::string why;
    const MeshPrimitive* bunny = test::cgalBunny(why);
    if (!bunny) {
        std::printf("bunny: skipped (%s)\n", why.c_str());
        return 0;
    }
    Scene b = test::makeBunnyScene(*bunny, width, width * 3 / 4);
    test::useLowRectLight(b);
    for (int k = 0; k < runs; ++k) {
        double cpu = 0.0;
        const OracleResult r = run(b, 0.01, PenumbraMethod::Exact, false, &cpu);
        const ExactPenumbraStats& e = *r.stats.lights[0].area->exact;
        std::printf(
            "bunny exact: run %.3f cpu s, pass %.3f s, occluders %llu, candidates %llu, covered "
            "%llu\n",
            cpu, e.seconds, (unsigned long long)e.occludersTotal,
            (unsigned long long)e.candidatesTotal, (unsigned long long)e.pixelsCovered);
    }
    return 0;
}

// Issue 55: the exact pass's cost per penumbra pixel by light type on one geometry. The shipped
// penumbra_square (a square occluder over a floor) at size x size under its rect light, then
// under a disk of the same area in the rect's place (emitting down) and a sphere of that radius
// at its centre. The exact pass finds its own pixels (--penumbra exact), one thread; its seconds
// (the shadow phase only), the best of `repeats`, per penumbra pixel (exact pixels with
// 0 < V < 1), and each type's ratio to the rect's; for disk and sphere the stated errors too.
int lightKinds(int size, int repeats) {
    Scene base = loadScene(SO_SCENES_DIR "/penumbra_square.scene.json");
    base.camera.width = base.camera.height = size;
    const Light rect = base.lights[0];
    const double area = glm::length(rect.wsU) * glm::length(rect.wsV);
    std::printf(
        "light kinds: penumbra_square at %dx%d, one thread, the exact pass's seconds (best of %d)\n"
        "%8s %10s %10s %10s %12s %8s %12s %12s\n",
        size, size, repeats, "light", "exact px", "penumbra", "pass s", "us/penumbra", "x rect",
        "error mean", "error max");
    double rectPerPixel = 0.0;
    for (const std::string kind : {"rect", "disk", "sphere"}) {
        Scene scene = base;
        Light& l = scene.lights[0];
        if (kind != "rect") {
            const double radius = std::sqrt(area / std::numbers::pi);
            l = kind == "disk" ? diskLight(l.name, l.wsPosition, {0, -1, 0}, radius)
                               : sphereLight(l.name, l.wsPosition, radius);
            finalizeScene(scene);
        }
        double best = 1e30;
        uint64_t exactPixels = 0, penumbra = 0;
        double errorMean = 0.0, errorMax = 0.0;
        for (int k = 0; k < repeats; ++k) {
            OracleOptions o;
            o.threads = 1;
            o.penumbra.method = PenumbraMethod::Exact;
            const OracleResult r = runOracle(scene, o);
            const ExactPenumbraStats& e = *r.stats.lights[0].area->exact;
            best = std::min(best, e.seconds);
            exactPixels = e.pixelsExact;
            const float* V = r.image.channel(l.name + ".V");
            const float* mask = r.image.channel(l.name + "." + channels::kExact);
            penumbra = 0;
            for (size_t i = 0; i < r.image.pixelCount(); ++i)
                penumbra += mask[i] == 1.0f && V[i] > 0.0f && V[i] < 1.0f;
            errorMean = e.boundHalfWidthSum / double(std::max<uint64_t>(e.pixelsExact, 1));
            errorMax = e.boundHalfWidthMax;
        }
        const double perPixel = best / double(std::max<uint64_t>(penumbra, 1));
        if (kind == "rect") rectPerPixel = perPixel;
        std::printf("%8s %10llu %10llu %10.4f %12.2f %8.2f %12.3g %12.3g\n", kind.c_str(),
                    (unsigned long long)exactPixels, (unsigned long long)penumbra, best,
                    1e6 * perPixel, perPixel / rectPerPixel, errorMean, errorMax);
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    int size = 64, maxK = 128, bunnyWidth = 160;
    double tightest = 1e-4;
    CLI::App app{"the exact penumbra pass's cost: growth with occluders, against RQMC"};
    app.add_option("--size", size, "the growth study's image side")->check(CLI::Range(16, 1024));
    app.add_option("--max-k", maxK, "the finest split of the occluder")->check(CLI::Range(1, 1024));
    app.add_option("--bunny-size", bunnyWidth, "the bunny image's width (height 3/4 of it)")
        ->check(CLI::Range(16, 1024));
    app.add_option("--tightest", tightest, "the tightest RQMC target run (0.01, 0.001 or 0.0001)")
        ->check(CLI::Range(1e-4, 0.01));
    int exactOnly = 0;
    app.add_option("--exact-only", exactOnly,
                   "run only the bunny's exact pass this many times (for a profiler), nothing else")
        ->check(CLI::Range(1, 1000));
    int kindsSize = 0, kindsRepeats = 3;
    app.add_option("--light-kinds", kindsSize,
                   "only the exact pass's cost per penumbra pixel of rect, disk and sphere lights "
                   "on penumbra_square at this side (issue 55), nothing else")
        ->check(CLI::Range(16, 1024));
    app.add_option("--repeats", kindsRepeats, "--light-kinds: runs per light, the best kept")
        ->check(CLI::Range(1, 100));
    CLI11_PARSE(app, argc, argv);
    if (exactOnly > 0) return exactOnlyRuns(bunnyWidth, exactOnly);
    if (kindsSize > 0) return lightKinds(kindsSize, kindsRepeats);
    growth(size, maxK);

    Scene square = loadScene(SO_SCENES_DIR "/penumbra_square.scene.json");
    square.camera.width = square.camera.height = 200;
    againstRqmc("penumbra_square", square, tightest);

    Scene chair = loadScene(SO_SCENES_DIR "/soft_chair.scene.json");
    std::erase_if(chair.lights,
                  [](const Light& l) { return std::string(lightTypeName(l.type)) != "rect"; });
    againstRqmc("soft_chair", chair, tightest);

    std::string why;
    const MeshPrimitive* bunny = test::cgalBunny(why);
    if (!bunny) {
        std::printf("\nbunny: skipped (%s)\n", why.c_str());
        return 0;
    }
    Scene b = test::makeBunnyScene(*bunny, bunnyWidth, bunnyWidth * 3 / 4);
    test::useLowRectLight(b);
    againstRqmc("bunny", b, tightest);
    return 0;
}
