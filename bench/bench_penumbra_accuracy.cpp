// What penumbra accuracy costs the oracle, against the exact answer: on the shipped
// penumbra_square scene (a rect light over a parallel square occluder, Lambert's closed form), the
// adaptive run at several targets: rays, seconds, the realised mean |V - exact| over penumbra
// pixels and the share of them inside their stated 95% interval (docs/benchmarks.md). The exact
// penumbra pass against RQMC: bench_exact_penumbra.
//
//   bench_penumbra_accuracy [--size N] [--baseline DIR ...]
//
// --baseline: `shadow-oracle trace` output folders of that scene at that size, e.g. traced by an
// earlier revision (the recorded baseline of docs/benchmarks.md): evaluated alike, and the rays
// this revision needs at their realised errors.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

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
    double penumbraP99 = 0.0;  // the 99th percentile of |V - exact| in the penumbra
    size_t penumbra = 0, agreeing = 0;
    double penumbraSpp = 0.0, agreeingSpp = 0.0;  // mean spp in the penumbra and elsewhere
};

Accuracy evaluate(const ChannelImage& img, double quantile) {
    namespace ch = channels;
    const float* A = img.channel(ch::kHit);
    const float* V = img.channel("panel.V");
    const float* SE = img.channel("panel.stderr");
    const float* spp = img.channel("panel.spp");
    Accuracy a;
    size_t covered = 0;
    std::vector<double> errors;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        const glm::dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i],
                           img.channel(ch::kPZ)[i]);
        const glm::dvec3 n(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i],
                           img.channel(ch::kNZ)[i]);
        const double exact = test::exactRectLightRectOccluderV(p, n, kLight, kOccluder);
        if (!(exact > 1e-9 && exact < 1.0 - 1e-9)) {
            ++a.agreeing;
            a.agreeingSpp += spp ? spp[i] : 0.0;
            continue;
        }
        ++a.penumbra;
        a.penumbraSpp += spp ? spp[i] : 0.0;
        a.penumbraMae += std::fabs(V[i] - exact);
        errors.push_back(std::fabs(V[i] - exact));
        covered += std::fabs(V[i] - exact) <= quantile * SE[i];
    }
    a.penumbraMae /= double(std::max<size_t>(a.penumbra, 1));
    if (!errors.empty()) {
        const size_t k = std::min(errors.size() - 1, size_t(0.99 * double(errors.size())));
        std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(k), errors.end());
        a.penumbraP99 = errors[k];
    }
    a.penumbraSpp /= double(std::max<size_t>(a.penumbra, 1));
    a.agreeingSpp /= double(std::max<size_t>(a.agreeing, 1));
    a.coverage = double(covered) / double(std::max<size_t>(a.penumbra, 1));
    return a;
}

// One run of either estimator: its rays and accuracy.
struct Run {
    std::string label;
    double rays = 0.0, seconds = 0.0;
    Accuracy a;
};

// The rays `runs` (sorted by rays) need for a given penumbra error, `metric` of Accuracy: log-log
// interpolation between the two runs around it; none outside their range.
std::optional<double> raysFor(const std::vector<Run>& runs, double error,
                              double Accuracy::*metric) {
    for (size_t k = 1; k < runs.size(); ++k) {
        const double e0 = runs[k - 1].a.*metric, e1 = runs[k].a.*metric;
        if (!(e0 >= error && error >= e1 && e0 > e1)) continue;
        const double t = std::log(error / e0) / std::log(e1 / e0);
        return std::exp(std::log(runs[k - 1].rays) +
                        t * (std::log(runs[k].rays) - std::log(runs[k - 1].rays)));
    }
    return std::nullopt;
}

// A recorded run of any revision: DIR/oracle.exr and DIR/oracle.json of `shadow-oracle trace`
// on penumbra_square at this size.
Run readRun(const std::string& dir) {
    Run r;
    r.label = dir;
    const ChannelImage img = readExr(dir + "/oracle.exr");
    std::ifstream in(dir + "/oracle.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    r.rays = j.at("lights").at(0).at("rays_traced").get<double>();
    r.seconds = j.at("lights").at(0).at("seconds").get<double>();
    // Files of other revisions state their intervals with their own quantile (1.96 before the
    // RQMC estimator): coverage is read with the 1.96 one, which is the more generous.
    r.a = evaluate(img, kZ95);
    return r;
}

void printRun(const Run& r) {
    std::printf("%-28s %12.0f %9.1f %9.1f %9.3f %14.6f %9.4f %10.6f\n", r.label.c_str(), r.rays,
                r.a.penumbraSpp, r.a.agreeingSpp, r.seconds, r.a.penumbraMae, r.a.coverage,
                r.a.penumbraP99);
}

// At each baseline run's realised error (mean, and 99th percentile), the rays this revision's
// runs need, interpolated.
void printEqualError(const std::vector<Run>& now, const std::vector<Run>& baseline) {
    std::printf("\nat equal realised penumbra error (this revision's rays interpolated):\n");
    for (const Run& b : baseline) {
        for (auto [name, metric] : {std::pair{"mean", &Accuracy::penumbraMae},
                                    std::pair{"p99", &Accuracy::penumbraP99}}) {
            const std::optional<double> rays = raysFor(now, b.a.*metric, metric);
            if (rays)
                std::printf("  %s: %s error %.6f: %.1f M rays here against %.1f M (%.2fx)\n",
                            b.label.c_str(), name, b.a.*metric, *rays / 1e6, b.rays / 1e6,
                            *rays / b.rays);
            else
                std::printf("  %s: %s error %.6f: outside this revision's range of targets\n",
                            b.label.c_str(), name, b.a.*metric);
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    int size = 200;
    std::vector<std::string> baselineDirs;
    CLI::App app{"penumbra accuracy against its cost, on the closed-form scene"};
    app.add_option("--size", size, "image side")->check(CLI::Range(16, 4096));
    app.add_option("--baseline", baselineDirs,
                   "trace output folders (oracle.exr, oracle.json) of a recorded baseline")
        ->check(CLI::ExistingDirectory);
    CLI11_PARSE(app, argc, argv);
    Scene scene = loadScene(SO_SCENES_DIR "/penumbra_square.scene.json");
    std::printf("penumbra_square %dx%d, adaptive:\n%-28s %12s %9s %9s %9s %14s %9s %10s\n", size,
                size, "run", "rays", "pen. spp", "else spp", "seconds", "penumbra mae", "coverage",
                "p99 error");
    std::vector<Run> now;
    bool reported = false;
    for (double target : {0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625, 0.0003125}) {
        OracleOptions o;
        o.width = o.height = size;
        o.area.targetError = target;
        const OracleResult r = runOracle(scene, o);
        const AreaShadowStats& la = *r.stats.lights[0].area;
        now.push_back({"target " + std::to_string(target), double(la.raysTraced), la.seconds,
                       evaluate(r.image, kIntervalQuantile95)});
        printRun(now.back());
        if (!reported && now.back().a.penumbraMae <= 5e-4) {
            std::printf("  first to reach penumbra mae 5e-4: target %g, %.3f s\n", target,
                        la.seconds);
            reported = true;
        }
    }
    if (baselineDirs.empty()) return 0;
    std::printf("\nrecorded baseline:\n");
    std::vector<Run> baseline;
    for (const std::string& dir : baselineDirs) {
        baseline.push_back(readRun(dir));
        printRun(baseline.back());
    }
    printEqualError(now, baseline);
    return 0;
}
