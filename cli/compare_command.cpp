#include "cli/compare_command.h"

#include <ctime>
#include <fstream>
#include <iostream>

#include "cli/csv_table.h"
#include "cli/output.h"
#include "cli/raster_command.h"
#include "core/error.h"
#include "core/gbuffer.h"
#include "oracle/points.h"
#include "raster_compare/compare/report.h"
#include "raster_compare/gl/gl_context.h"

namespace so {

namespace fs = std::filesystem;

ImageSpec parseImageSpec(const std::string& text) {
    const auto eq = text.find('=');
    const std::string label = text.substr(0, std::min(eq, text.size()));
    const std::string path = eq == std::string::npos ? "" : text.substr(eq + 1);
    if (label.empty() || path.empty())
        throwInputError("command line", "--image",
                        "\"" + printable(text, 60) + "\" is not LABEL=PATH");
    return makeImageSpec(label, path);
}

namespace {

// The techniques as the user named them; a spec the library refuses is named with its flag.
std::vector<TechniqueSpec> parseTechniques(const CompareOptions& options) {
    std::vector<TechniqueSpec> specs;
    for (const std::string& s : options.techniques)
        specs.push_back(asFlag("--technique", [&] { return parseTechniqueSpec(s); }));
    return specs;
}

// What the command line can get wrong, said with its flags, before anything is read.
void checkCommandLine(const CompareOptions& options, const std::vector<TechniqueSpec>& specs) {
    if (specs.empty() && options.images.empty())
        throwInputError("command line", "--technique",
                        "nothing to compare: give --technique NAME or --image LABEL=PATH");
    for (const TechniqueSpec& spec : specs)
        createTechniqueOfFlag("--technique", spec.name, spec.settings);
    asFlag("--image", [&] { checkRowLabels(specs, options.images); });
    if (!options.pointsPath.empty()) {
        if (!specs.empty())
            throwInputError("command line", "--points",
                            "judges images only: the built-in techniques render the scene's "
                            "camera, not the G-buffer's pixels (drop --technique)");
        if (options.raster.width > 0 || options.raster.height > 0)
            throwInputError("command line", "--points",
                            "the image is the G-buffer's size: drop --width and --height");
    }
    if (options.pathFrames > 0 && !options.images.empty())
        throwInputError("command line", "--frames-path",
                        "an image is one frame: --frames-path works with --technique only");
}

// The oracle: at the G-buffer's points (never cached: the cache is keyed by a camera), or from the
// cache when the same scene content and options were traced before.
CachedOracle oracleFor(const CompareOptions& options, const Scene& scene,
                       const OracleOptions& oracleOptions, const GBuffer* points) {
    if (!points) {
        CachedOracle oracle = namingFlag("verify", "--verify", [&] {
            return traceOrLoad(scene, oracleOptions, {options.cacheDir, options.useCache});
        });
        printWarnings(oracle.warnings);
        return oracle;
    }
    OracleResult r = namingFlag("verify", "--verify",
                                [&] { return runOracleAtPoints(scene, *points, oracleOptions); });
    return {std::move(r.image), std::move(r.stats), false, "points " + points->path};
}

// The long form (a row per metric) and the wide form (a row per light of a row).
void writeCsvs(const fs::path& out, const std::string& scenePath, const nlohmann::json& metrics) {
    std::ofstream csv(out / "metrics.csv");
    WideCsv wide;
    csv << "scene,light,technique,label,metric,value\n";
    for (const nlohmann::json& result : metrics["results"]) {
        const std::string technique = result["technique"], label = result["label"];
        for (const auto& [light, row] : result["lights"].items()) {
            std::vector<std::pair<std::string, std::string>> cells = {
                {"scene", scenePath}, {"light", light}, {"technique", technique}, {"label", label}};
            for (const auto& [name, value] : result["parameters"].items())
                cells.emplace_back("param." + name, value.dump());
            for (const auto& [metric, value] : flatMetrics(row)) {
                const std::string text = value.is_null() ? "" : value.dump();
                csv << csvField(scenePath) << ',' << csvField(light) << ',' << csvField(technique)
                    << ',' << csvField(label) << ',' << metric << ',' << text << "\n";
                cells.emplace_back(metric, text);
            }
            wide.add(cells);
        }
    }
    wide.write(out / "metrics_wide.csv");
}

// The error EXR of one row: per light, one channel per artifact class and the error.
void writeErrorExr(const fs::path& path, const ReportTechnique& rt) {
    ChannelImage errors(rt.image.width(), rt.image.height());
    for (const LightComparison& lc : rt.lights) {
        for (const ArtifactClass& c : kArtifactClasses) {
            const std::vector<float>& plane = lc.maps.of(c.id);
            std::copy(plane.begin(), plane.end(), errors.addChannel(lc.light + "." + c.layer));
        }
        std::copy(lc.maps.error.begin(), lc.maps.error.end(),
                  errors.addChannel(lc.light + "." + kErrorLayer));
    }
    writeExr(path.string(), errors);
}

// A row's folder: raster.json always, its image and error EXR unless a sweep task drops them.
void writeRowFiles(const fs::path& out, const ComparedRow& row, bool images) {
    const fs::path dir = out / row.report.fileLabel;
    std::error_code ec;
    fs::create_directories(dir, ec);
    ExrAttributes attributes = {{"shadowOracle/technique", row.report.label}};
    if (row.source == "external") {
        attributes.emplace_back("shadowOracle/image", row.imagePath);
        writeJsonFile(dir / "raster.json", {{"source", "external"},
                                            {"image", row.imagePath},
                                            {"renderer", row.renderer},
                                            {"params", row.parameters}});
    } else {
        writeJsonFile(dir / "raster.json", toJson(*row.stats));
    }
    if (!images) return;
    writeExr((dir / "raster.exr").string(), row.report.image, attributes);
    writeErrorExr(out / ("error_" + row.report.fileLabel + ".exr"), row.report);
}

// The report's provenance table: what made it, as a person reads it.
std::vector<std::pair<std::string, std::string>> provenance(const nlohmann::json& metrics,
                                                            const CachedOracle& oracle,
                                                            const OracleOptions& o) {
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    const auto& tool = metrics["tool"];
    const nlohmann::json gl = metrics["gl"].is_object() ? metrics["gl"] : nlohmann::json::object();
    char sampling[160];
    std::snprintf(sampling, sizeof sampling,
                  "target error %g, agreement target %g, max spp %d, fixed spp %d, seed %u",
                  o.area.targetError, o.area.agreementTarget, o.area.maxSpp, o.area.fixedSpp,
                  o.area.seed);
    return {{"tool", tool.value("name", "") + " " + tool.value("version", "")},
            {"git revision", tool.value("git_revision", "")},
            {"GL renderer", gl.value("renderer", "") + " (" + gl.value("version", "") + ", " +
                                gl.value("platform", "") + ")"},
            {"scene", metrics["scene"].value("file", "")},
            {"scene hash", metrics["scene"].value("hash", "")},
            {"image",
             std::to_string(oracle.image.width()) + " x " + std::to_string(oracle.image.height())},
            {"oracle", std::string(oracle.fromCache ? "from the cache" : "traced") + ", key " +
                           metrics["oracle"].value("key", "")},
            {"oracle area sampling", sampling},
            {"date", date}};
}

// Who measured the report's times: the GL renderer for the techniques, and for images the
// renderers their cost files name.
std::string timedOn(const Comparison& comparison) {
    std::vector<std::string> renderers;
    bool images = false;
    for (const ComparedRow& row : comparison.rows) {
        if (row.source != "external") continue;
        images = true;
        if (!row.renderer.empty() &&
            std::find(renderers.begin(), renderers.end(), row.renderer) == renderers.end())
            renderers.push_back(row.renderer);
    }
    std::string own;
    for (const std::string& name : renderers) own += (own.empty() ? "" : ", ") + name;
    const std::string gl = comparison.gl ? comparison.gl->renderer : "";
    if (!images) return gl;
    if (own.empty()) return gl.empty() ? "none: the images have no cost files" : gl;
    return gl.empty() ? own + " (the images' cost files)" : gl + "; the images by " + own;
}

void writeReportFile(const fs::path& out, const std::string& scenePath, const Scene& scene,
                     const CachedOracle& oracle, Comparison& comparison,
                     const nlohmann::json& metrics, const OracleOptions& oracleOptions,
                     bool embedImages) {
    ReportInput report;
    report.sceneFile = scenePath;
    for (const Light& l : scene.lights) report.lights.push_back(l.name);
    report.oracle = oracle.image;
    report.timedOn = timedOn(comparison);
    for (ComparedRow& row : comparison.rows) report.techniques.push_back(std::move(row.report));
    report.oracleCurves = comparison.oracleCurves;
    report.oracleExact = comparison.oracleExact;
    report.embedImages = embedImages;
    report.provenance = provenance(metrics, oracle, oracleOptions);
    if (comparison.path) {
        report.pathFrames = comparison.path->frames;
        report.flickerStrips = std::move(comparison.path->strips);
    }
    writeReport((out / "report.html").string(), report);
}

int verifyExitCode(const CompareOptions& options, const OracleStats& stats) {
    if (!stats.verified()) return 0;
    const uint64_t bad = stats.disagreements();
    std::cout << "  oracle verified: " << bad << " disagreements\n";
    if (!bad) return 0;
    std::cerr << "error: " << options.scenePath << ": verify: " << bad
              << " pixels where the oracle disagrees with the exact re-trace (metrics.json "
                 "oracle.stats.verify)\n";
    return 3;
}

ComparisonOptions comparisonOptions(const CompareOptions& options,
                                    const OracleOptions& oracleOptions) {
    ComparisonOptions c;
    c.raster = options.raster;
    c.boundaryRadius = options.boundaryRadius;
    c.contactThresholdRelative = options.contactThresholdRelative;
    c.pathFrames = options.pathFrames;
    c.pathOracle = oracleOptions;
    c.pathCache = {options.cacheDir, options.useCache};
    // The camera path's frames, a line each as they are done (the library reports, the command
    // prints); the techniques' own progress is the "rendering" lines below.
    c.progress = [](const ProgressUpdate& u) {
        if (u.stage == "camera path frames")
            std::cerr << "camera path: frame " << u.done << " of " << u.total << "\n";
        return true;
    };
    c.renderingGroup = [](const std::vector<std::string>& labels) {
        std::cerr << "rendering";
        for (size_t i = 0; i < labels.size(); ++i) std::cerr << (i ? ", " : " ") << labels[i];
        std::cerr << (labels.size() > 1 ? " (frames interleaved)" : "") << "\n";
    };
    return c;
}

}  // namespace

CompareRun compareScene(const CompareOptions& options) {
    // Everything the user can get wrong is checked before any work starts.
    const std::vector<TechniqueSpec> techniques = parseTechniques(options);
    checkCommandLine(options, techniques);
    CompareRun run;
    run.scene = loadScene(options.scenePath);
    const Scene& scene = run.scene;
    printSceneWarnings(options.scenePath, scene);
    if (options.pathFrames > 0 && !scene.cameraPath)
        throwInputError(options.scenePath, "camera_path",
                        "missing: --frames-path needs the scene's camera path (scene_format 2, "
                        "docs/scene-format.md)");
    run.oracleOptions = options.oracle;
    if (options.raster.width > 0) run.oracleOptions.width = options.raster.width;
    if (options.raster.height > 0) run.oracleOptions.height = options.raster.height;
    std::optional<GBuffer> points;
    if (!options.pointsPath.empty()) points = readGBuffer(options.pointsPath);
    const CameraDesc camera = effectiveCamera(scene, run.oracleOptions);
    const int width = points ? points->width : camera.width,
              height = points ? points->height : camera.height;
    std::vector<ImageInput> images;
    for (const ImageSpec& spec : options.images)
        images.push_back({spec, readVisibilityImage(spec.path, scene.lights, width, height,
                                                    options.imageEncoding)});
    if (!options.outDir.empty()) run.out = makeOutputDir(options.outDir);

    run.atPoints = points.has_value();
    run.oracle = oracleFor(options, scene, run.oracleOptions, points ? &*points : nullptr);
    run.comparison = compareWithOracle(scene, run.oracle, techniques, images,
                                       comparisonOptions(options, run.oracleOptions));
    printWarnings(run.comparison.warnings);
    return run;
}

int writeCompareOutputs(const CompareOptions& options, CompareRun& run) {
    const fs::path& out = run.out;
    SO_CHECK(!out.empty());
    const Scene& scene = run.scene;
    if (options.writeReport)
        writeExr((out / "oracle.exr").string(), run.oracle.image,
                 {{"shadowOracle/sceneHash", scene.contentHash}});
    for (const ComparedRow& row : run.comparison.rows) writeRowFiles(out, row, options.writeImages);
    const nlohmann::json metrics =
        metricsJson(scene, options.scenePath, run.oracle, run.comparison, options.boundaryRadius);
    writeJsonFile(out / "metrics.json", metrics);
    writeCsvs(out, options.scenePath, metrics);
    if (options.writeReport)
        writeReportFile(out, options.scenePath, scene, run.oracle, run.comparison, metrics,
                        run.oracleOptions, options.embedImages);
    std::cout << "compared " << options.scenePath << ": " << options.techniques.size()
              << " techniques, " << options.images.size() << " images, oracle "
              << (run.atPoints           ? "at the G-buffer's points"
                  : run.oracle.fromCache ? "from the cache"
                                         : "traced")
              << "\n  " << (out / "metrics.json").string() << "\n  "
              << (out / "metrics.csv").string() << "\n  " << (out / "metrics_wide.csv").string()
              << "\n";
    return verifyExitCode(options, run.oracle.stats);
}

int runCompareCommand(const CompareOptions& options) {
    CompareRun run = compareScene(options);
    return writeCompareOutputs(options, run);
}

}  // namespace so
