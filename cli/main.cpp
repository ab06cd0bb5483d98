// shadow-oracle: one program, one subcommand per job (docs/cli.md). Exit codes: 0 success,
// 2 bad input (one line on stderr naming the file and field), 1 anything else.
#include <functional>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/compare_command.h"
#include "cli/export_command.h"
#include "cli/gate_command.h"
#include "cli/index_command.h"
#include "cli/metrics_command.h"
#include "cli/raster_command.h"
#include "cli/sweep_command.h"
#include "cli/sweep_merge.h"
#include "cli/sweep_task.h"
#include "cli/techniques_command.h"
#include "cli/trace_command.h"
#include "cli/trace_merge_command.h"
#include "cli/view_command.h"
#include "core/error.h"
#include "core/version.h"
#include "oracle/exact_penumbra.h"
#include "raster_compare/gl/gl_context.h"
#include "raster_compare/gl/technique.h"

// --width and --height, the same for every subcommand that renders.
static void addImageSize(CLI::App* cmd, int& width, int& height) {
    cmd->add_option("--width", width, "image width (default: the scene camera's)")
        ->check(CLI::Range(1, 16384));
    cmd->add_option("--height", height, "image height (default: the scene camera's)")
        ->check(CLI::Range(1, 16384));
}

// Each subcommand is added with its options; what is returned runs it once parsed. Options live
// in shared_ptrs because CLI11 writes into them during parsing, after these functions return.
using Runner = std::function<int()>;

// --quiet: no progress output. `progress` is a field of the command's options, which its Runner
// keeps alive.
static void addQuiet(CLI::App* cmd, bool& progress) {
    cmd->add_flag_callback(
        "--quiet", [&progress] { progress = false; }, "no progress output");
}

// --penumbra and --exact-pixels (docs/oracle.md, "Exact penumbrae"): names, read when the
// command runs so that a bad one is the tool's one-line error.
struct PenumbraFlags {
    std::string method = "auto", pixels = "penumbra";
    so::DiskBoundOptions bound;
    void applyTo(so::OracleOptions& o) const {
        o.penumbra.method = so::parsePenumbraMethod(method, "command line", "--penumbra");
        o.penumbra.allPixels = so::parseExactPixels(pixels, "command line", "--exact-pixels");
        o.penumbra.bound = so::checkedBoundOptions(bound, "command line", "--bound-max-sides");
    }
};
static std::shared_ptr<PenumbraFlags> addPenumbraFlags(CLI::App* cmd) {
    auto flags = std::make_shared<PenumbraFlags>();
    cmd->add_option("--penumbra", flags->method,
                    "auto (default: per light, exact or sampled, whichever a probe estimates "
                    "cheaper), sampled (RQMC with 95% intervals), exact (rect lights: clipped "
                    "polygons on every pixel, stderr 0 there; disk and sphere lights: V in a "
                    "guaranteed interval, NAME.bound) or both (V sampled, V_exact beside it)");
    cmd->add_option("--exact-pixels", flags->pixels,
                    "with --penumbra both: penumbra (pixels whose samples disagree, default) or "
                    "all (every sampled pixel); exact finds its own pixels");
    cmd->add_option("--bound-target", flags->bound.targetHalfWidth,
                    "disk and sphere lights with --penumbra exact, both or auto: the half-width "
                    "of V's guaranteed interval to reach (default 1e-6)")
        ->check(CLI::Range(1e-7, 0.5));
    cmd->add_option("--bound-max-sides", flags->bound.maxSides,
                    "the most sides of the polygons bounding a disk, a power of two in [32, " +
                        std::to_string(so::kMaxDiskSides) +
                        "] (default 4096); a pixel stopped by it states the half-width it reached");
    return flags;
}

static Runner addTrace(CLI::App& app) {
    auto o = std::make_shared<so::TraceCommandOptions>();
    CLI::App* traceCmd = app.add_subcommand(
        "trace", "ground-truth shadows with Embree: oracle.exr, oracle.json, previews");
    traceCmd->add_option("scene", o->scenePath, "scene file (.json, .gltf or .glb)")->required();
    traceCmd->add_option("--out", o->outDir, "output folder (created if missing)")->required();
    addImageSize(traceCmd, o->oracle.width, o->oracle.height);
    traceCmd->add_option("--threads", o->oracle.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    traceCmd->add_option("--seed", o->oracle.area.seed,
                         "seed of the area-light sample sequences (default 0)");
    traceCmd
        ->add_option(
            "--target-error", o->oracle.area.targetError,
            "area lights: stop a pixel when its 95% half-width is below this (default 0.01)")
        ->check(CLI::Range(1e-4, 0.5));
    traceCmd
        ->add_option("--agreement-target", o->oracle.area.agreementTarget,
                     "area lights: a pixel whose samples all agree (lit, or umbra) stops at the "
                     "larger of this and --target-error (default 0.01; docs/oracle.md)")
        ->check(CLI::Range(1e-4, 0.5));
    traceCmd
        ->add_option("--max-spp", o->oracle.area.maxSpp,
                     "area lights: most samples per pixel (default 16384)")
        ->check(CLI::Range(16, 1 << 20));
    auto* sppOpt =
        traceCmd
            ->add_option("--spp", o->oracle.area.fixedSpp,
                         "area lights: exactly this many samples per pixel (no adaptivity)")
            ->check(CLI::Range(1, 1 << 20));
    sppOpt->excludes("--target-error");
    sppOpt->excludes("--max-spp");
    sppOpt->excludes("--agreement-target");
    addQuiet(traceCmd, o->progress);
    traceCmd->add_flag_callback(
        "--no-previews", [o] { o->previews = false; },
        "write no NAME.png previews (then OpenImageIO is not loaded)");
    traceCmd
        ->add_option("--verify", o->oracle.verify.pixels,
                     "re-trace N random pixels per light (plus up to N near the horizon) with an "
                     "independent exact tracer; exit 3 on any disagreement")
        ->check(CLI::Range(0, 1 << 20));
    traceCmd
        ->add_option("--verify-samples", o->oracle.verify.areaSamples,
                     "reference samples per area-light pixel checked (default 4096)")
        ->check(CLI::Range(64, 1 << 20));
    // Checked by the command (one line naming --tile, exit 2), not by CLI11.
    traceCmd->add_option("--tile", o->tile,
                         "I/N: trace only band I of N bands of rows (0 <= I < N <= 4096), for "
                         "`trace-merge` to join; not with --verify");
    traceCmd->add_option(
        "--points", o->pointsPath,
        "GBUFFER.exr: the oracle at a renderer's own surface points (P, N, A), one "
        "result per pixel of that image (docs/external.md); not with --tile, "
        "--width, --height");
    const std::shared_ptr<PenumbraFlags> penumbra = addPenumbraFlags(traceCmd);

    return [o, penumbra] {
        penumbra->applyTo(o->oracle);
        return so::runTraceCommand(*o);
    };
}

static Runner addTraceMerge(CLI::App& app) {
    auto o = std::make_shared<so::TraceMergeOptions>();
    CLI::App* mergeCmd = app.add_subcommand(
        "trace-merge", "join the folders of `trace --tile I/N` into the whole oracle.exr");
    mergeCmd->add_option("tiles", o->tileDirs, "output folders of trace --tile, one per band")
        ->required();
    mergeCmd->add_option("--out", o->outDir, "output folder (created if missing)")->required();
    addQuiet(mergeCmd, o->progress);

    return [o] { return so::runTraceMergeCommand(*o); };
}

static Runner addView(CLI::App& app) {
    auto o = std::make_shared<so::ViewCommandOptions>();
    CLI::App* viewCmd = app.add_subcommand(
        "view",
        "the exact view for another renderer: view.json (camera and light matrices) and "
        "gbuffer.exr (docs/external.md)");
    viewCmd->add_option("scene", o->scenePath, "scene file (.json, .gltf or .glb)")->required();
    viewCmd->add_option("--out", o->outDir, "output folder (created if missing)")->required();
    addImageSize(viewCmd, o->oracle.width, o->oracle.height);
    viewCmd->add_option("--threads", o->oracle.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    addQuiet(viewCmd, o->progress);
    return [o] { return so::runViewCommand(*o); };
}

static Runner addExport(CLI::App& app) {
    auto o = std::make_shared<so::ExportCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "export",
        "the scene for any engine: scene.glb (world-space meshes, camera, KHR_lights_punctual), "
        "scene.scene.json, view.json, gbuffer.exr (docs/export.md)");
    cmd->add_option("scene", o->scenePath, "scene file (.json, .gltf or .glb)")->required();
    cmd->add_option("--out", o->outDir, "output folder (created if missing)")->required();
    addImageSize(cmd, o->oracle.width, o->oracle.height);
    cmd->add_option("--threads", o->oracle.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    addQuiet(cmd, o->progress);
    return [o] { return so::runExportCommand(*o); };
}

static Runner addRaster(CLI::App& app) {
    auto o = std::make_shared<so::RasterCommandOptions>();
    std::string techniqueHelp;
    for (const so::TechniqueInfo* t : so::allTechniques())
        techniqueHelp += "\n  " + t->name + ": " + t->summary;
    CLI::App* rasterCmd = app.add_subcommand(
        "raster", "render with an OpenGL shadow technique: raster.exr, raster.json, previews");
    rasterCmd->add_option("scene", o->scenePath, "scene file (.json, .gltf or .glb)")->required();
    rasterCmd->add_option("--out", o->outDir, "output folder (created if missing)")->required();
    rasterCmd->add_option("--technique", o->technique, "shadow technique:" + techniqueHelp)
        ->required();
    rasterCmd->add_option(
        "--set", o->settings,
        "technique parameter key=value (repeatable; `shadow-oracle techniques` lists them)");
    addImageSize(rasterCmd, o->raster.width, o->raster.height);
    rasterCmd
        ->add_option(
            "--frames", o->raster.frames,
            "timed frames after 2 warm-up frames, median and quartiles reported (default 9)")
        ->check(CLI::Range(1, 1000));

    return [o] { return so::runRasterCommand(*o); };
}

static Runner addCompare(CLI::App& app) {
    auto o = std::make_shared<so::CompareOptions>();
    auto noCache = std::make_shared<bool>(false);
    CLI::App* compareCmd = app.add_subcommand(
        "compare", "the oracle against techniques: metrics.json, metrics.csv, error EXRs");
    compareCmd->add_option("scene", o->scenePath, "scene file (.json, .gltf or .glb)")->required();
    compareCmd->add_option("--out", o->outDir, "output folder (created if missing)")->required();
    compareCmd->add_option("--technique", o->techniques, "NAME[:key=value,...] (repeatable)");
    auto images = std::make_shared<std::vector<std::string>>();
    compareCmd->add_option("--image", *images,
                           "LABEL=PATH: a renderer's shadow image (EXR with NAME.V per light, or "
                           "a grey PNG), judged like a technique; PATH.json beside it gives its "
                           "cost (repeatable; docs/external.md)");
    auto encoding = std::make_shared<std::string>("linear");
    compareCmd->add_option("--image-encoding", *encoding,
                           "how a PNG's codes are V: linear (V = code / max, default) or srgb");
    compareCmd->add_option("--points", o->pointsPath,
                           "GBUFFER.exr: the oracle at a renderer's own G-buffer points instead of "
                           "the scene camera's pixels (with --image only; trace --points)");
    addImageSize(compareCmd, o->raster.width, o->raster.height);
    compareCmd
        ->add_option(
            "--frames", o->raster.frames,
            "timed frames per technique after 2 warm-up frames, techniques interleaved (default 9)")
        ->check(CLI::Range(1, 1000));
    compareCmd->add_option("--threads", o->oracle.threads, "oracle threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    compareCmd->add_option("--seed", o->oracle.area.seed, "oracle area-light seed (default 0)");
    compareCmd
        ->add_option("--target-error", o->oracle.area.targetError,
                     "oracle area-light target (default 0.01)")
        ->check(CLI::Range(1e-4, 0.5));
    compareCmd
        ->add_option("--agreement-target", o->oracle.area.agreementTarget,
                     "oracle: where an area light's samples all agree, the target "
                     "(default 0.01)")
        ->check(CLI::Range(1e-4, 0.5));
    compareCmd
        ->add_option("--verify", o->oracle.verify.pixels,
                     "re-trace N random pixels per light (plus up to N near the horizon) of the "
                     "oracle with an independent exact tracer; exit 3 on any disagreement")
        ->check(CLI::Range(0, 1 << 20));
    compareCmd->add_option("--cache", o->cacheDir,
                           "oracle cache folder (default: $XDG_CACHE_HOME/shadow-oracle)");
    compareCmd->add_flag("--no-cache", *noCache, "always trace the oracle, and do not store it");
    compareCmd->add_flag("--embed-images", o->embedImages,
                         "report.html with its images inside (one file); default: PNGs in "
                         "report_images/ beside it");
    compareCmd
        ->add_option("--boundary-radius", o->boundaryRadius, "r of docs/metrics.md (default 2)")
        ->check(CLI::Range(0, 64));
    compareCmd
        ->add_option("--frames-path", o->pathFrames,
                     "also render N frames along the scene's camera_path (oracle and every "
                     "technique) for temporal_flicker_rate (docs/metrics.md)")
        ->check(CLI::Range(2, 10000));
    const std::shared_ptr<PenumbraFlags> penumbra = addPenumbraFlags(compareCmd);

    return [o, noCache, encoding, images, penumbra] {
        penumbra->applyTo(o->oracle);
        o->useCache = !*noCache;
        for (const std::string& text : *images) o->images.push_back(so::parseImageSpec(text));
        o->imageEncoding = so::parseImageEncoding(*encoding, "command line", "--image-encoding");
        return so::runCompareCommand(*o);
    };
}

static Runner addSweep(CLI::App& app) {
    auto o = std::make_shared<so::SweepOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sweep",
        "every setting of a sweep spec over its scenes: locally or as Slurm job arrays, "
        "resumable, merged into metrics.csv and a report with Pareto fronts");
    cmd->add_option("spec", o->specPath, "sweep spec (docs/sweep.md)")->required();
    cmd->add_option("--out", o->outDir, "the sweep's folder (created; rerun to resume)")
        ->required();
    auto* jobs = cmd->add_option("--jobs", o->jobs, "tasks at once on this machine (default 1)")
                     ->check(CLI::Range(1, 1024));
    auto* slurm = cmd->add_flag("--slurm", o->slurm,
                                "submit job arrays to Slurm instead (DIR on a shared file system)");
    slurm->excludes(jobs);
    cmd->add_option("--partition", o->slurmOptions.partition, "Slurm partition")->needs(slurm);
    cmd->add_option("--max-concurrent", o->slurmOptions.maxConcurrent,
                    "Slurm: at most K array tasks at once (--array=...%K)")
        ->check(CLI::Range(1, 1000000))
        ->needs(slurm);
    cmd->add_option("--sbatch-arg", o->slurmOptions.sbatchArgs,
                    "Slurm: an #SBATCH line for every script, e.g. --sbatch-arg=--time=10 "
                    "(repeatable)")
        ->needs(slurm);
    cmd->add_flag("--dry-run", o->slurmOptions.dryRun,
                  "Slurm: write and print the batch scripts, submit nothing")
        ->needs(slurm);
    addQuiet(cmd, o->progress);
    return [o] { return so::runSweepCommand(*o); };
}

static Runner addSweepTask(CLI::App& app) {
    auto o = std::make_shared<so::SweepTaskOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sweep-task", "one task of a planned sweep (what `sweep` and its Slurm arrays run)");
    cmd->add_option("dir", o->dir, "the sweep's folder (holding sweep.json)")->required();
    auto* index = cmd->add_option("--index", o->index,
                                  "task K of the plan, a technique's or an image's (from 0)")
                      ->check(CLI::Range(0L, 100000000L));
    cmd->add_option("--oracle", o->oracle, "the oracle of scene S (from 0)")
        ->check(CLI::Range(0L, 100000000L))
        ->excludes(index);
    return [o] { return so::runSweepTask(*o); };
}

static Runner addSweepMerge(CLI::App& app) {
    auto o = std::make_shared<so::SweepMergeOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sweep-merge",
        "a sweep's finished tasks into metrics.csv, metrics.json and report.html; "
        "exit 1 listing the tasks that did not finish");
    cmd->add_option("dir", o->dir, "the sweep's folder (holding sweep.json)")->required();
    cmd->add_flag("--quiet", o->quiet, "do not list the unfinished tasks");
    return [o] { return so::runSweepMerge(*o); };
}

static Runner addGate(CLI::App& app) {
    auto o = std::make_shared<so::GateOptions>();
    CLI::App* gateCmd = app.add_subcommand(
        "gate",
        "limits on metrics.json, and a baseline run, as an exit code: 0 all hold, 1 a limit fails "
        "or a metric regressed, 2 bad input");
    gateCmd->add_option("metrics", o->metricsPath, "metrics.json from compare")->required();
    gateCmd->add_option("--limits", o->limitsPath, "limits file (docs/gate.md)");
    gateCmd->add_option("--baseline", o->baselinePath,
                        "the last good run's metrics.json: fail where a metric got worse "
                        "(docs/gate.md#baseline)");
    gateCmd->add_option("--junit", o->junitPath, "also write JUnit XML here");
    gateCmd->add_option("--summary", o->summaryPath,
                        "also write a Markdown summary here (for a pull request comment)");

    return [o] { return so::runGateCommand(*o); };
}

static Runner addIndex(CLI::App& app) {
    auto o = std::make_shared<so::IndexOptions>();
    CLI::App* indexCmd = app.add_subcommand(
        "index", "one HTML page over compare outputs: per metric, techniques x scene x light");
    indexCmd->add_option("dirs", o->dirs, "output folders of compare (each with metrics.json)")
        ->required();
    indexCmd->add_option("--out", o->outPath,
                         "the page (default: index.html in the folder holding every DIR)");

    return [o] { return so::runIndexCommand(*o); };
}

static Runner addTechniques(CLI::App& app) {
    auto json = std::make_shared<bool>(false), markdown = std::make_shared<bool>(false);
    CLI::App* techniquesCmd = app.add_subcommand(
        "techniques", "list the techniques with their parameters, defaults and ranges");
    auto* jsonFlag = techniquesCmd->add_flag("--json", *json, "as JSON (format_version 3)");
    techniquesCmd->add_flag("--markdown", *markdown, "as the Markdown of docs/techniques.md")
        ->excludes(jsonFlag);

    return [json, markdown] {
        return so::runTechniquesCommand(*json       ? so::ListingFormat::Json
                                        : *markdown ? so::ListingFormat::Markdown
                                                    : so::ListingFormat::Text);
    };
}

static Runner addMetrics(CLI::App& app) {
    auto markdown = std::make_shared<bool>(false);
    CLI::App* metricsCmd = app.add_subcommand(
        "metrics", "list the metrics with their units, which way is better and where they apply");
    metricsCmd->add_flag("--markdown", *markdown, "as the Markdown table of docs/metrics.md");

    return [markdown] { return so::runMetricsCommand(*markdown); };
}

int main(int argc, char** argv) {
    CLI::App app{"shadow-oracle: how wrong are your real-time shadows?"};
    app.require_subcommand(1);
    app.set_version_flag("--version",
                         std::string(so::kToolVersion) + " (" + so::kGitRevision + ")");
    const std::vector<std::pair<std::string, Runner>> commands = {
        {"trace", addTrace(app)},
        {"trace-merge", addTraceMerge(app)},
        {"view", addView(app)},
        {"export", addExport(app)},
        {"raster", addRaster(app)},
        {"compare", addCompare(app)},
        {"sweep", addSweep(app)},
        {"sweep-task", addSweepTask(app)},
        {"sweep-merge", addSweepMerge(app)},
        {"gate", addGate(app)},
        {"index", addIndex(app)},
        {"techniques", addTechniques(app)},
        {"metrics", addMetrics(app)}};
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? 0 : 2;
    }
    try {
        for (const auto& [name, run] : commands)
            if (app.got_subcommand(name)) return run();
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
