// What penumbra accuracy costs the oracle, against the exact answer: on the shipped
// penumbra_square scene (a rect light over a parallel square occluder, Lambert's closed form), the
// adaptive run at several targets: rays, seconds, the realised mean |V - exact| over penumbra
// pixels and the share of them inside their stated 95% interval (docs/benchmarks.md).
//
//   bench_penumbra_accuracy [--size N] [--exr oracle.exr ...]
//
// --exr evaluates existing oracle.exr files of that scene at that size instead (e.g. traced by an
// earlier revision: the recorded baseline of docs/benchmarks.md).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/channels.h"
#include "core/image.h"
#include "core/scene.h"
#include "lambert.h"
#include "oracle/area_shadow.h"
#include "oracle/oracle.h"

using namespace so;

namespace {

// The scene's light and occluder (scenes/make_scenes.py: penumbra_square).
const test::AxisRect kLight{4.0, -0.5, 1.5, -0.5, 1.0};
const test::AxisRect kOccluder{1.5, -1.0, 1.0, -1.0, 1.0};

struct Accuracy {
    double penumbraMae = 0.0, coverage = 0.0;
    size_t penumbra = 0;
};

Accuracy evaluate(const ChannelImage& img, double quantile) {
    namespace ch = channels;
    const float* A = img.channel(ch::kHit);
    const float* V = img.channel("panel.V");
    const float* SE = img.channel("panel.stderr");
    Accuracy a;
    size_t covered = 0;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        const glm::dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i],
                           img.channel(ch::kPZ)[i]);
        const glm::dvec3 n(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i],
                           img.channel(ch::kNZ)[i]);
        const double exact = test::exactRectLightRectOccluderV(p, n, kLight, kOccluder);
        if (!(exact > 1e-9 && exact < 1.0 - 1e-9)) continue;
        ++a.penumbra;
        a.penumbraMae += std::fabs(V[i] - exact);
        covered += std::fabs(V[i] - exact) <= quantile * SE[i];
    }
    a.penumbraMae /= double(std::max<size_t>(a.penumbra, 1));
    a.coverage = double(covered) / double(std::max<size_t>(a.penumbra, 1));
    return a;
}

}  // namespace

int main(int argc, char** argv) {
    int size = 200;
    std::vector<std::string> exrs;
    CLI::App app{"penumbra accuracy against its cost, on the closed-form scene"};
    app.add_option("--size", size, "image side")->check(CLI::Range(16, 4096));
    app.add_option("--exr", exrs, "evaluate these oracle.exr files instead");
    CLI11_PARSE(app, argc, argv);
    if (!exrs.empty()) {
        for (const std::string& path : exrs) {
            // Files of other revisions state their intervals with their own quantile: both given.
            const ChannelImage img = readExr(path);
            const Accuracy t = evaluate(img, kIntervalQuantile95), z = evaluate(img, kZ95);
            std::printf(
                "%s: penumbra mean |V - exact| %.6f over %zu pixels; coverage %.4f (t "
                "quantile) or %.4f (1.96)\n",
                path.c_str(), t.penumbraMae, t.penumbra, t.coverage, z.coverage);
        }
        return 0;
    }
    Scene scene = loadScene(SO_SCENES_DIR "/penumbra_square.scene.json");
    std::printf("penumbra_square %dx%d, adaptive:\n%8s %12s %9s %9s %14s %9s\n", size, size,
                "target", "rays", "mean spp", "seconds", "penumbra mae", "coverage");
    bool reported = false;
    for (double target : {0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625}) {
        OracleOptions o;
        o.progress = false;
        o.width = o.height = size;
        o.area.targetError = target;
        const OracleResult r = runOracle(scene, o);
        const OracleAreaStats& la = *r.stats.lights[0].area;
        const Accuracy a = evaluate(r.image, kIntervalQuantile95);
        std::printf("%8.6f %12llu %9.1f %9.3f %14.6f %9.4f\n", target,
                    (unsigned long long)la.raysTraced, la.sppMean(), la.seconds, a.penumbraMae,
                    a.coverage);
        if (!reported && a.penumbraMae <= 5e-4) {
            std::printf("  first to reach penumbra mae 5e-4: target %g, %.3f s\n", target,
                        la.seconds);
            reported = true;
        }
    }
    return 0;
}
