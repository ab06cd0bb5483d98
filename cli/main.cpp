// shadow-oracle: one program, one subcommand per job (docs/cli.md). Exit codes: 0 success,
// 2 bad input (one line on stderr naming the file and field), 1 anything else.
#include <functional>
#include <iostream>
#include <map>
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
#include "cli/sweep_task_command.h"
#include "cli/techniques_command.h"
#include "cli/trace_command.h"
#include "cli/trace_merge_command.h"
#include "cli/view_command.h"
#include "core/error.h"
#include "core/version.h"
#include "oracle/oracle.h"
#include "oracle/trace_options.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/raster_options.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/gl/technique_listing.h"

// A trace option read straight into an int by a command that does not trace (view, export,
// raster): the row's flag, help and range.
static void addTraceOptionInt(CLI::App* cmd, const std::string& key, int& target) {
    const so::TraceOptionSpec& s = so::traceOption(key);
    cmd->add_option(s.cli, target, so::traceOptionHelp(s))
        ->check(CLI::Range(int(s.min), int(s.max)));
}

// --width and --height of the commands that render without tracing: the trace options' ranges.
static void addImageSize(CLI::App* cmd, int& width, int& height) {
    addTraceOptionInt(cmd, "width", width);
    addTraceOptionInt(cmd, "height", height);
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

// The options of a table (core/option_table.h: names, ranges, help) that a command offers, read
// into `values` as CLI11 parses them; the table checks what it alone can (a name, a power of two)
// and its kind's apply function writes them into the library's options when the command runs, so
// that a bad one is the tool's one-line error naming the flag.
struct OptionFlags {
    so::OptionValues values;
};
// How the command line names a field in errors: by its flag.
static const so::OptionNaming kCliNaming{"command line", /*cliNames=*/true, "", false};

static std::shared_ptr<OptionFlags> addTableOptions(CLI::App* cmd, const so::OptionTable& table,
                                                    so::OptionSurface surface) {
    auto flags = std::make_shared<OptionFlags>();
    OptionFlags* f = flags.get();  // the command's Runner keeps it alive
    std::map<std::string, CLI::Option*> added;
    for (const so::OptionSpec& s : table.rows) {
        if (!(s.surfaces & surface)) continue;
        const std::string key = s.key, help = so::optionHelp(s);
        CLI::Option* opt = nullptr;
        if (s.type == so::OptionType::Integer) {
            opt = cmd->add_option_function<int64_t>(
                s.cli,
                [f, key](const int64_t& v) {
                    f->values[key] = {double(v), ""};
                },
                help);
            if (!s.powerOfTwo) opt->check(CLI::Range(int64_t(s.min), int64_t(s.max)));
        } else if (s.type == so::OptionType::Real) {
            opt = cmd->add_option_function<double>(
                s.cli,
                [f, key](const double& v) {
                    f->values[key] = {v, ""};
                },
                help);
            opt->check(CLI::Range(s.min, s.max));
        } else if (s.type == so::OptionType::Flag) {
            opt = cmd->add_flag_function(
                s.cli,
                [f, key](int64_t) {
                    f->values[key] = {1.0, ""};
                },
                help);
        } else {
            opt = cmd->add_option_function<std::string>(
                s.cli,
                [f, key](const std::string& v) {
                    f->values[key] = {0.0, v};
                },
                help);
        }
        added[key] = opt;
    }
    for (const so::OptionSpec& s : table.rows)
        for (const std::string& other : s.excludes)
            if (added.count(s.key) && added.count(other)) added[s.key]->excludes(added[other]);
    return flags;
}

static Runner addTrace(CLI::App& app) {
    auto o = std::make_shared<so::TraceCommandOptions>();
    CLI::App* traceCmd = app.add_subcommand(
        "trace", "ground-truth shadows with Embree: oracle.exr, oracle.json, previews");
    traceCmd->add_option("scene", o->scenePath, "scene file (.json, .gltf or .glb)")->required();
    traceCmd->add_option("--out", o->outDir, "output folder (created if missing)")->required();
    const std::shared_ptr<OptionFlags> traceOptions =
        addTableOptions(traceCmd, so::traceOptions(), so::kSurfaceTrace);
    addQuiet(traceCmd, o->progress);
    traceCmd->add_flag_callback(
        "--no-previews", [o] { o->previews = false; },
        "write no NAME.png previews (then OpenImageIO is not loaded)");
    // Checked by the command (one line naming --tile, exit 2), not by CLI11.
    traceCmd->add_option("--tile", o->tile,
                         "I/N: trace only band I of N bands of rows (0 <= I < N <= 4096), for "
                         "`trace-merge` to join; not with --verify");
    traceCmd->add_option("--frame", o->frame,
                         "K: the oracle at frame K of the scene's sequence (t = K / fps)");
    traceCmd->add_option("--frames", o->frames,
                         "A:B: the oracle at frames A to B (both included) of the sequence, each "
                         "into DIR/frame_NNNN/");
    traceCmd->add_option(
        "--points", o->pointsPath,
        "GBUFFER.exr: the oracle at a renderer's own surface points (P, N, A), one "
        "result per pixel of that image (docs/external.md); not with --tile, "
        "--width, --height");

    return [o, traceOptions] {
        so::applyTraceOptions(traceOptions->values, kCliNaming, o->oracle);
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
    addTraceOptionInt(viewCmd, "threads", o->oracle.threads);
    viewCmd->add_option(
        "--frame", o->frame,
        "K: the scene posed at frame K of its sequence (t = K / fps), as trace --frame");
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
    addTraceOptionInt(cmd, "threads", o->oracle.threads);
    cmd->add_option(
        "--frame", o->frame,
        "K: the scene posed at frame K of its sequence (t = K / fps), as trace --frame");
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
    const std::shared_ptr<OptionFlags> rasterOptions =
        addTableOptions(rasterCmd, so::rasterOptionTable(), so::kSurfaceRaster);
    // --converge: the comparison table's row, which `raster` shares.
    const std::shared_ptr<OptionFlags> frameOptions =
        addTableOptions(rasterCmd, so::compareOptionTable(), so::kSurfaceRaster);

    return [o, rasterOptions, frameOptions] {
        so::applyRasterOptions(rasterOptions->values, kCliNaming, o->raster);
        so::checkOptions(so::compareOptionTable(), frameOptions->values, kCliNaming);
        if (const auto it = frameOptions->values.find("converge"); it != frameOptions->values.end())
            o->raster.converge = int(it->second.number);
        return so::runRasterCommand(*o);
    };
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
    const std::shared_ptr<OptionFlags> traceOptions =
        addTableOptions(compareCmd, so::traceOptions(), so::kSurfaceCompare);
    const std::shared_ptr<OptionFlags> rasterOptions =
        addTableOptions(compareCmd, so::rasterOptionTable(), so::kSurfaceCompare);
    const std::shared_ptr<OptionFlags> compareOptions =
        addTableOptions(compareCmd, so::compareOptionTable(), so::kSurfaceCompare);
    compareCmd->add_option("--cache", o->cacheDir,
                           "oracle cache folder (default: $XDG_CACHE_HOME/shadow-oracle)");
    compareCmd->add_flag("--no-cache", *noCache, "always trace the oracle, and do not store it");
    compareCmd->add_flag("--embed-images", o->embedImages,
                         "report.html with its images inside (one file); default: PNGs in "
                         "report_images/ beside it");
    auto progress = std::make_shared<bool>(true);
    addQuiet(compareCmd, *progress);

    return [o, noCache, encoding, images, traceOptions, rasterOptions, compareOptions, progress] {
        so::applyTraceOptions(traceOptions->values, kCliNaming, o->oracle);
        so::applyRasterOptions(rasterOptions->values, kCliNaming, o->raster);
        so::applyCompareOptions(compareOptions->values, kCliNaming, *o);
        // One size for the oracle and the renders.
        o->raster.width = o->oracle.width;
        o->raster.height = o->oracle.height;
        o->useCache = !*noCache;
        for (const std::string& text : *images) o->images.push_back(so::parseImageSpec(text));
        o->imageEncoding = so::parseImageEncoding(*encoding, "command line", "--image-encoding");
        return so::runCompareCommand(*o, *progress);
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
    auto* jsonFlag = techniquesCmd->add_flag(
        "--json", *json,
        "as JSON (format_version " + std::to_string(so::kTechniquesJsonFormat) + ")");
    techniquesCmd->add_flag("--markdown", *markdown, "as the Markdown of docs/techniques.md")
        ->excludes(jsonFlag);

    return [json, markdown] {
        return so::runTechniquesCommand(*json       ? so::ListingFormat::Json
                                        : *markdown ? so::ListingFormat::Markdown
                                                    : so::ListingFormat::Text);
    };
}

// `trace-options`, `raster-options`, `compare-options`: a table as Markdown or JSON.
static Runner addOptionListing(CLI::App& app, const std::string& name, const std::string& what,
                               const so::OptionTable& table) {
    auto json = std::make_shared<bool>(false), markdown = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand(
        name, "list the " + what +
                  " with their API and sweep keys, defaults, ranges and the commands that take "
                  "them");
    auto* jsonFlag = cmd->add_flag("--json", *json, "as JSON (format_version 1)");
    cmd->add_flag("--markdown", *markdown, "as the Markdown table of docs/cli.md")
        ->excludes(jsonFlag);
    return [json, markdown, &table] {
        std::cout << (*json ? so::optionsJson(table) : so::optionsMarkdown(table));
        return 0;
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
        {"trace-options",
         addOptionListing(app, "trace-options", "oracle's options", so::traceOptions())},
        {"raster-options", addOptionListing(app, "raster-options", "raster path's timing options",
                                            so::rasterOptionTable())},
        {"compare-options", addOptionListing(app, "compare-options", "comparison's options",
                                             so::compareOptionTable())},
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
