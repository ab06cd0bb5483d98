#include "cli/compare_command.h"

#include <iostream>

#include "cli/output.h"
#include "cli/raster_command.h"
#include "core/error.h"
#include "core/gbuffer.h"
#include "oracle/points.h"
#include "raster_compare/gl/gl_context.h"
#include "raster_compare/pipeline/compare_output.h"

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
    SO_CHECK(!run.out.empty());
    CompareOutputOptions output;
    output.scenePath = options.scenePath;
    output.boundaryRadius = options.boundaryRadius;
    output.sampling = run.oracleOptions.area;
    output.writeReport = options.writeReport;
    output.embedImages = options.embedImages;
    output.writeImages = options.writeImages;
    const CompareOutputFiles files =
        writeCompareOutput(run.out, run.scene, run.oracle, run.comparison, output);
    std::cout << "compared " << options.scenePath << ": " << options.techniques.size()
              << " techniques, " << options.images.size() << " images, oracle "
              << (run.atPoints           ? "at the G-buffer's points"
                  : run.oracle.fromCache ? "from the cache"
                                         : "traced")
              << "\n  " << files.metricsJson.string() << "\n  " << files.metricsCsv.string()
              << "\n  " << files.metricsWideCsv.string() << "\n";
    return verifyExitCode(options, run.oracle.stats);
}

int runCompareCommand(const CompareOptions& options) {
    CompareRun run = compareScene(options);
    return writeCompareOutputs(options, run);
}

}  // namespace so
