// shadow-oracle: one program, one subcommand per job (docs/cli.md). Exit codes: 0 success,
// 2 bad input (one line on stderr naming the file and field), 1 anything else.
#include <iostream>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "core/version.h"
#include "oracle/trace_command.h"
#include "raster_compare/compare_command.h"
#include "raster_compare/gate_command.h"
#include "raster_compare/gl_context.h"
#include "raster_compare/raster_command.h"
#include "raster_compare/technique.h"

// --width and --height, the same for every subcommand that renders.
static void addImageSize(CLI::App* cmd, int& width, int& height) {
    cmd->add_option("--width", width, "image width (default: the scene camera's)")
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--height", height, "image height (default: the scene camera's)")
        ->check(CLI::Range(1, 16384));
}

int main(int argc, char** argv) {
    CLI::App app{"shadow-oracle: how wrong are your real-time shadows?"};
    app.require_subcommand(1);
    app.set_version_flag("--version",
                         std::string(so::kToolVersion) + " (" + so::kGitRevision + ")");

    so::TraceCommandOptions trace;
    CLI::App* traceCmd = app.add_subcommand(
        "trace", "ground-truth shadows with Embree: oracle.exr, oracle.json, previews");
    traceCmd->add_option("scene", trace.scenePath, "scene file (.json, .gltf or .glb)")->required();
    traceCmd->add_option("--out", trace.outDir, "output folder (created if missing)")->required();
    addImageSize(traceCmd, trace.oracle.width, trace.oracle.height);
    traceCmd->add_option("--threads", trace.oracle.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    traceCmd->add_option("--seed", trace.oracle.area.seed,
                         "seed of the area-light sample sequences (default 0)");
    traceCmd
        ->add_option(
            "--target-error", trace.oracle.area.targetError,
            "area lights: stop a pixel when its 95% half-width is below this (default 0.01)")
        ->check(CLI::Range(1e-4, 0.5));
    traceCmd
        ->add_option("--max-spp", trace.oracle.area.maxSpp,
                     "area lights: most samples per pixel (default 16384)")
        ->check(CLI::Range(16, 1 << 20));
    auto* sppOpt =
        traceCmd
            ->add_option("--spp", trace.oracle.area.fixedSpp,
                         "area lights: exactly this many samples per pixel (no adaptivity)")
            ->check(CLI::Range(1, 1 << 20));
    sppOpt->excludes("--target-error");
    sppOpt->excludes("--max-spp");
    bool quiet = false;
    traceCmd->add_flag("--quiet", quiet, "no progress output");
    traceCmd
        ->add_option("--verify", trace.oracle.verify.pixels,
                     "re-trace N random pixels per light (plus up to N near the horizon) with an "
                     "independent exact tracer; exit 3 on any disagreement")
        ->check(CLI::Range(0, 1 << 20));
    traceCmd
        ->add_option("--verify-samples", trace.oracle.verify.areaSamples,
                     "reference samples per area-light pixel checked (default 4096)")
        ->check(CLI::Range(64, 1 << 20));

    so::RasterCommandOptions raster;
    std::string techniqueHelp;
    for (const so::ShadowTechnique* t : so::allTechniques())
        techniqueHelp += "\n  " + t->name() + ": " + t->summary();
    CLI::App* rasterCmd = app.add_subcommand(
        "raster", "render with an OpenGL shadow-map technique: raster.exr, raster.json, previews");
    rasterCmd->add_option("scene", raster.scenePath, "scene file (.json, .gltf or .glb)")
        ->required();
    rasterCmd->add_option("--out", raster.outDir, "output folder (created if missing)")->required();
    rasterCmd->add_option("--technique", raster.technique, "shadow technique:" + techniqueHelp)
        ->required();
    rasterCmd->add_option("--set", raster.settings,
                          "technique parameter key=value (repeatable; see docs/techniques.md)");
    addImageSize(rasterCmd, raster.raster.width, raster.raster.height);
    rasterCmd
        ->add_option("--frames", raster.raster.frames, "timed frames, median reported (default 5)")
        ->check(CLI::Range(1, 1000));

    so::CompareOptions compare;
    CLI::App* compareCmd = app.add_subcommand(
        "compare", "the oracle against techniques: metrics.json, metrics.csv, error EXRs");
    compareCmd->add_option("scene", compare.scenePath, "scene file (.json, .gltf or .glb)")
        ->required();
    compareCmd->add_option("--out", compare.outDir, "output folder (created if missing)")
        ->required();
    compareCmd->add_option("--technique", compare.techniques, "NAME[:key=value,...] (repeatable)")
        ->required();
    addImageSize(compareCmd, compare.raster.width, compare.raster.height);
    compareCmd
        ->add_option("--frames", compare.raster.frames, "timed frames per technique (default 5)")
        ->check(CLI::Range(1, 1000));
    compareCmd
        ->add_option("--threads", compare.oracle.threads, "oracle threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    compareCmd->add_option("--seed", compare.oracle.area.seed,
                           "oracle area-light seed (default 0)");
    compareCmd
        ->add_option("--target-error", compare.oracle.area.targetError,
                     "oracle area-light target (default 0.01)")
        ->check(CLI::Range(1e-4, 0.5));
    compareCmd
        ->add_option("--verify", compare.oracle.verify.pixels,
                     "re-trace N random pixels per light (plus up to N near the horizon) of the "
                     "oracle with an independent exact tracer; exit 3 on any disagreement")
        ->check(CLI::Range(0, 1 << 20));
    compareCmd->add_option("--cache", compare.cacheDir,
                           "oracle cache folder (default: $XDG_CACHE_HOME/shadow-oracle)");
    bool noCache = false;
    compareCmd->add_flag("--no-cache", noCache, "always trace the oracle, and do not store it");
    compareCmd
        ->add_option("--boundary-radius", compare.boundaryRadius,
                     "r of docs/metrics.md (default 2)")
        ->check(CLI::Range(0, 64));

    so::GateOptions gate;
    CLI::App* gateCmd = app.add_subcommand(
        "gate", "limits on metrics.json as an exit code: 0 all hold, 1 a limit fails, 2 bad input");
    gateCmd->add_option("metrics", gate.metricsPath, "metrics.json from compare")->required();
    gateCmd->add_option("--limits", gate.limitsPath, "limits file (docs/gate.md)")->required();
    gateCmd->add_option("--junit", gate.junitPath, "also write JUnit XML here");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? 0 : 2;
    }
    trace.oracle.progress = !quiet;
    compare.useCache = !noCache;
    compare.oracle.progress = false;
    try {
        if (app.got_subcommand(traceCmd)) return so::runTraceCommand(trace);
        if (app.got_subcommand(rasterCmd)) return so::runRasterCommand(raster);
        if (app.got_subcommand(compareCmd)) return so::runCompareCommand(compare);
        if (app.got_subcommand(gateCmd)) return so::runGateCommand(gate);
    } catch (const so::GlUnavailable& e) {
        std::cerr << "error: no OpenGL: " << e.what() << std::endl;
        return 1;
    } catch (const so::InputError& e) {
        std::cerr << e.what() << std::endl;
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << std::endl;
        return 1;
    }
    return 1;
}
