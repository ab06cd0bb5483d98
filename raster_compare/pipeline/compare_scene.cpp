#include "raster_compare/pipeline/compare_scene.h"

#include <map>
#include <optional>

#include "core/error.h"
#include "core/gbuffer.h"
#include "core/scene_pose.h"
#include "oracle/points.h"
#include "raster_compare/pipeline/option_errors.h"

namespace so {

namespace {

// The techniques as the caller named them; a spec the library refuses is named with its option.
std::vector<TechniqueSpec> parseTechniques(const CompareOptions& options) {
    std::vector<TechniqueSpec> specs;
    for (const std::string& s : options.techniques)
        specs.push_back(asFlag(options.names.source, options.names.technique,
                               [&] { return parseTechniqueSpec(s); }));
    return specs;
}

// What the caller's options can get wrong, said with their names, before anything is read.
void checkOptions(const CompareOptions& options, const std::vector<TechniqueSpec>& specs) {
    const CompareOptionNames& n = options.names;
    SO_CHECK(!n.source.empty());  // the caller names its options (CompareOptionNames)
    if (specs.empty() && options.images.empty())
        throwInputError(
            n.source, n.technique,
            "nothing to compare: give " + n.technique + " NAME or " + n.image + " LABEL=PATH");
    for (const TechniqueSpec& spec : specs)
        createTechniqueOfFlag(n.source, n.technique, spec.name, spec.settings);
    asFlag(n.source, n.image, [&] { checkRowLabels(specs, options.images); });
    if (!options.pointsPath.empty()) {
        checkTechniquesAtPoints(true, specs.size(), n.source, n.points, n.technique);
        if (options.raster.width > 0 || options.raster.height > 0)
            throwInputError(n.source, n.points, "the image is the G-buffer's size: drop " + n.size);
    }
    if (options.sequence && options.pathFrames > 0)
        throwInputError(n.source, n.sequence,
                        "one or the other: " + n.sequence + " judges the scene's own sequence, " +
                            n.framesPath + " its camera path");
    if (options.sequence && (!options.images.empty() || !options.pointsPath.empty()))
        throwInputError(
            n.source, n.sequence,
            "an image is one frame: " + n.sequence + " works with " + n.technique + " only");
    if (options.convergeFrames > 0 && (options.sequence || options.pathFrames > 0))
        throwInputError(n.source, n.converge,
                        "one or the other: " + n.converge + " judges still frames, " + n.sequence +
                            " the scene's sequence and " + n.framesPath + " its camera path");
    if (options.convergeFrames > 0 && (!options.images.empty() || !options.pointsPath.empty()))
        throwInputError(
            n.source, n.converge,
            "an image is one frame: " + n.converge + " works with " + n.technique + " only");
    if (options.pathFrames > 0 && !options.images.empty())
        throwInputError(
            n.source, n.framesPath,
            "an image is one frame: " + n.framesPath + " works with " + n.technique + " only");
}

void warnAll(const CompareCallbacks& callbacks, const std::vector<std::string>& warnings,
             const std::string& prefix = "") {
    if (!callbacks.warning) return;
    for (const std::string& w : warnings) callbacks.warning(prefix + w);
}

// The oracle: at the G-buffer's points (never cached: the cache is keyed by a camera), or from the
// cache when the same scene content and options were traced before.
CachedOracle oracleFor(const CompareOptions& options, const CompareCallbacks& callbacks,
                       const Scene& scene, const OracleOptions& oracleOptions,
                       const GBuffer* points) {
    const std::string& verify = options.names.verify;
    if (!points) {
        CachedOracle oracle = namingFlag("verify", verify, [&] {
            return traceOrLoad(scene, oracleOptions, {options.cacheDir, options.useCache});
        });
        warnAll(callbacks, oracle.warnings);
        return oracle;
    }
    OracleResult r = namingFlag("verify", verify,
                                [&] { return runOracleAtPoints(scene, *points, oracleOptions); });
    CachedOracle oracle{std::move(r.image), std::move(r.stats), false, "points " + points->path};
    oracle.atPoints = true;
    return oracle;
}

// The index of a sequence's last frame.
int lastFrame(const Scene& scene) {
    return scene.sequence->frames - 1;
}

// `scene`: as loaded, with its motion.
ComparisonOptions comparisonOptions(const CompareOptions& options,
                                    const CompareCallbacks& callbacks,
                                    const OracleOptions& oracleOptions, const Scene& scene) {
    ComparisonOptions c;
    c.raster = options.raster;
    c.boundaryRadius = options.boundaryRadius;
    c.contactThresholdRelative = options.contactThresholdRelative;
    c.pathFrames = options.pathFrames;
    c.pathOracle = oracleOptions;
    c.pathCache = {options.cacheDir, options.useCache};
    if (options.sequence) c.sequence = &scene;
    c.convergeFrames = options.convergeFrames;
    c.progress = callbacks.progress;
    c.renderingGroup = callbacks.renderingGroup;
    return c;
}

using CompareSetter = void (*)(CompareOptions& o, const OptionValue& v);

// Where each key of the compare option table goes.
const std::map<std::string, CompareSetter>& compareSetters() {
    static const std::map<std::string, CompareSetter> kSetters = {
        {"boundary_radius",
         [](CompareOptions& o, const OptionValue& v) { o.boundaryRadius = int(v.number); }},
        {"frames_path",
         [](CompareOptions& o, const OptionValue& v) { o.pathFrames = int(v.number); }},
        {"sequence", [](CompareOptions& o, const OptionValue& v) { o.sequence = v.number != 0.0; }},
        {"converge",
         [](CompareOptions& o, const OptionValue& v) { o.convergeFrames = int(v.number); }},
    };
    return kSetters;
}

}  // namespace

void applyCompareOptions(const OptionValues& values, const OptionNaming& naming,
                         CompareOptions& o) {
    so::checkOptions(compareOptionTable(), values, naming);
    for (const auto& [key, value] : values) compareSetters().at(key)(o, value);
}

std::vector<std::string> appliedCompareOptionKeys() {
    std::vector<std::string> keys;
    for (const auto& [key, setter] : compareSetters()) keys.push_back(key);
    return keys;
}

CompareRun compareScene(const CompareOptions& options, const CompareCallbacks& callbacks) {
    // Everything the caller can get wrong is checked before any work starts.
    const std::vector<TechniqueSpec> techniques = parseTechniques(options);
    checkOptions(options, techniques);
    CompareRun run;
    run.scene = loadScene(options.scenePath);
    const Scene& scene = run.scene;
    warnAll(callbacks, scene.stats.warnings, options.scenePath + ": ");
    if (options.pathFrames > 0 && !scene.cameraPath)
        throwInputError(options.scenePath, "camera_path",
                        "missing: " + options.names.framesPath +
                            " needs the scene's camera path (scene_format 2, "
                            "docs/scene-format.md)");
    if (options.sequence && !scene.sequence)
        throwInputError(options.scenePath, "sequence",
                        "missing: " + options.names.sequence +
                            " needs the scene's sequence (scene_format 5, docs/scene-format.md)");
    // In a sequence, the ordinary comparison is the last frame's: the scene posed there.
    const Scene posed = options.sequence
                            ? sceneAtTime(scene, sequenceTime(*scene.sequence, lastFrame(scene)))
                            : Scene();
    const Scene& compared = options.sequence ? posed : scene;
    run.oracleOptions = options.oracle;
    if (options.raster.width > 0) run.oracleOptions.width = options.raster.width;
    if (options.raster.height > 0) run.oracleOptions.height = options.raster.height;
    std::optional<GBuffer> points;
    if (!options.pointsPath.empty()) points = readGBuffer(options.pointsPath);
    const CameraDesc camera = effectiveCamera(compared, run.oracleOptions);
    const int width = points ? points->width : camera.width,
              height = points ? points->height : camera.height;
    std::vector<ImageInput> images;
    for (const ImageSpec& spec : options.images)
        images.push_back({spec, readVisibilityImage(spec.path, scene.lights, width, height,
                                                    options.imageEncoding)});
    if (!options.outDir.empty()) run.out = makeOutputDir(options.outDir, options.names.out);

    run.atPoints = points.has_value();
    run.oracle =
        oracleFor(options, callbacks, compared, run.oracleOptions, points ? &*points : nullptr);
    run.comparison =
        compareWithOracle(compared, run.oracle, techniques, images,
                          comparisonOptions(options, callbacks, run.oracleOptions, scene));
    warnAll(callbacks, run.comparison.warnings);
    return run;
}

CompareOutputFiles writeCompareRun(const CompareOptions& options, CompareRun& run) {
    SO_CHECK(!run.out.empty());
    CompareOutputOptions output;
    output.scenePath = options.scenePath;
    output.boundaryRadius = options.boundaryRadius;
    output.sampling = run.oracleOptions.area;
    output.writeReport = options.writeReport;
    output.embedImages = options.embedImages;
    output.writeImages = options.writeImages;
    return writeCompareOutput(run.out, run.scene, run.oracle, run.comparison, output);
}

}  // namespace so
