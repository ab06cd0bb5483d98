#include "cli/compare_command.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

#include "cli/compare_path.h"
#include "cli/csv_table.h"
#include "cli/output.h"
#include "core/camera_path.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/gbuffer.h"
#include "oracle/points.h"
#include "raster_compare/compare/report.h"
#include "raster_compare/compare/tradeoff.h"
#include "raster_compare/gl/gl_context.h"

namespace so {

namespace fs = std::filesystem;

namespace {

// The label made safe for file names: letters, digits, '-' and '.' kept, anything else '_'.
std::string fileLabelOf(const std::string& label) {
    std::string out;
    for (char c : label) out += (std::isalnum((unsigned char)c) || c == '-' || c == '.') ? c : '_';
    return out;
}

}  // namespace

TechniqueSpec parseTechniqueSpec(const std::string& spec) {
    TechniqueSpec t;
    t.label = spec;
    const auto colon = spec.find(':');
    t.name = spec.substr(0, colon);
    if (t.name.empty())
        throwInputError("command line", "--technique",
                        "empty technique name in \"" + printable(spec, 60) + "\"");
    if (colon != std::string::npos) {
        std::string rest = spec.substr(colon + 1);
        size_t start = 0;
        while (start <= rest.size()) {
            const size_t comma = rest.find(',', start);
            const std::string kv =
                rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            if (!kv.empty()) t.settings.push_back(kv);
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
    }
    t.fileLabel = fileLabelOf(spec);
    return t;
}

ImageSpec makeImageSpec(const std::string& label, const std::string& path) {
    return {label, fileLabelOf(label), path};
}

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

// A technique as the user asked for it, created (and so validated) before any work starts.
struct TechniqueRun {
    TechniqueSpec spec;
    std::unique_ptr<Technique> technique;
};

// Everything one compare run shares between its techniques.
struct CompareJob {
    const CompareOptions& options;
    const Scene& scene;
    const CachedOracle& oracle;
    const GlContext* gl;  // null when only images are compared: no GL needed
    MetricOptions metricOptions;
    fs::path out;
    std::ofstream csv;
    WideCsv wide;
    // Per light, the oracle's penumbra cost curve (oraclePenumbraCurve): for every technique's
    // oracle_ms_at_equal_error and for the report.
    std::vector<std::vector<std::pair<double, double>>> oracleCurves;
    std::optional<PathFlicker> path;  // --frames-path
};

// What the light's own passes and the visibility pass cost (docs/metrics.md, cost).
// Several light passes (none today) add up (core/timing.h).
TechniqueCost techniqueCost(const RasterStats& stats, size_t li, double oracleSeconds) {
    TechniqueCost cost;
    cost.visibilityMs = cost.shadowMapMs = TimingStats{};
    for (const auto& [pass, t] : stats.lights[li].passMs)
        *(pass == "visibility" ? cost.visibilityMs : cost.shadowMapMs) += t;
    cost.frameMs = stats.timings.wallMs;
    cost.cameraMs = stats.timings.cameraMs;
    cost.memoryBytes = stats.lights[li].memoryBytes;
    cost.oracleSeconds = oracleSeconds;  // what the ground truth cost, so every row has both
    return cost;
}

// The long form (a row per metric) and a row of the wide form.
// `row`: the light's row of metrics.json.
void writeCsvRows(CompareJob& job, const std::string& technique, const std::string& label,
                  const std::vector<std::pair<std::string, nlohmann::json>>& params,
                  const std::string& light, const nlohmann::json& row) {
    const std::vector<std::pair<std::string, nlohmann::json>> rows = flatMetrics(row);
    std::vector<std::pair<std::string, std::string>> wide = {{"scene", job.options.scenePath},
                                                             {"light", light},
                                                             {"technique", technique},
                                                             {"label", label}};
    for (const auto& [name, value] : params) wide.emplace_back("param." + name, value.dump());
    for (const auto& [metric, value] : rows) {
        const std::string text = value.is_null() ? "" : value.dump();
        job.csv << csvField(job.options.scenePath) << ',' << csvField(light) << ','
                << csvField(technique) << ',' << csvField(label) << ',' << metric << ',' << text
                << "\n";
        wide.emplace_back(metric, text);
    }
    job.wide.add(wide);
}

// The error EXR of one technique: per light, one channel per artifact class and the error.
void writeErrorExr(const fs::path& path, const std::vector<LightComparison>& lights, int w, int h) {
    ChannelImage errors(w, h);
    for (const LightComparison& lc : lights) {
        for (const ArtifactClass& c : kArtifactClasses) {
            const std::vector<float>& plane = lc.maps.of(c.id);
            std::copy(plane.begin(), plane.end(), errors.addChannel(lc.light + "." + c.layer));
        }
        std::copy(lc.maps.error.begin(), lc.maps.error.end(),
                  errors.addChannel(lc.light + "." + kErrorLayer));
    }
    writeExr(path.string(), errors);
}

// The oracle's cost curve for one light as the report and tradeoff.h take it: (ms, mean stated 95%
// half-width over the penumbra's pixels), the time pro rata of the samples; empty for hard lights.
std::vector<std::pair<double, double>> oraclePenumbraCurve(const OracleLightStats& l) {
    std::vector<std::pair<double, double>> curve;
    if (l.area && l.area->samples)
        for (const CostPoint& p : l.area->costCurve)
            if (p.penumbraMeanHalfWidth)
                curve.emplace_back(
                    1e3 * l.area->seconds * double(p.samples) / double(l.area->samples),
                    *p.penumbraMeanHalfWidth);
    return curve;
}

// The curve key and quality value of a setting (TradeoffPoint): the name and every parameter but
// the quality one.
void setCurve(ReportTechnique& rt, const TechniqueRun& run) {
    const ParamSpec* q = qualityParam(findTechnique(run.spec.name).params);
    rt.curve = run.spec.name;
    for (const auto& [key, value] : run.technique->values().all()) {
        if (q && key == q->name) {
            rt.quality = value;
            continue;
        }
        // The shortest form that reads back as the same double: 0.1, not 0.10000000000000001.
        char text[32];
        for (int digits = 15; digits <= 17; ++digits) {
            std::snprintf(text, sizeof text, "%.*g", digits, value);
            if (std::strtod(text, nullptr) == value) break;
        }
        rt.curve += " " + key + "=" + text;
    }
}

// One technique's render measured against the oracle per light, its files and CSV rows written;
// `row` gets its entry of metrics.json's results.
ReportTechnique compareTechnique(CompareJob& job, size_t index, const TechniqueRun& run,
                                 RasterResult&& r, nlohmann::json& row) {
    const fs::path dir = job.out / run.spec.fileLabel;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (job.options.writeImages)
        writeExr((dir / "raster.exr").string(), r.image,
                 {{"shadowOracle/technique", run.spec.label}});
    writeJsonFile(dir / "raster.json", toJson(r.stats));
    job.metricOptions.filteredTechnique = run.technique->filtered();
    ReportTechnique rt;
    rt.label = run.spec.label;
    rt.family = findTechnique(run.spec.name).family;
    setCurve(rt, run);
    rt.fileLabel = run.spec.fileLabel;
    for (const auto& [key, value] : run.technique->values().all()) {
        char text[48];
        std::snprintf(text, sizeof text, "%s%s=%.10g", rt.parameters.empty() ? "" : " ",
                      key.c_str(), value);
        rt.parameters += text;
    }
    const nlohmann::json settings = toJson(run.technique->values().settings());
    std::vector<std::pair<std::string, nlohmann::json>> params;
    for (const auto& [name, value] : settings.items()) params.emplace_back(name, value);
    nlohmann::json lights = nlohmann::json::object();
    for (size_t li = 0; li < job.scene.lights.size(); ++li) {
        LightComparison lc;
        lc.light = job.scene.lights[li].name;
        lc.metrics =
            computeLightMetrics(job.oracle.image, r.image, lc.light, job.metricOptions, &lc.maps);
        lc.cost = techniqueCost(r.stats, li, job.oracle.stats.lights[li].seconds());
        if (job.path) lc.temporal = job.path->flicker[index][li];
        if (lc.metrics.penumbraMae)
            lc.cost.oracleMsAtEqualError =
                oracleMsAtError(job.oracleCurves[li], *lc.metrics.penumbraMae);
        lights[lc.light] = lc.toJson();
        writeCsvRows(job, run.spec.name, run.spec.label, params, lc.light, lights[lc.light]);
        rt.lights.push_back(std::move(lc));
    }
    if (job.options.writeImages)
        writeErrorExr(job.out / ("error_" + run.spec.fileLabel + ".exr"), rt.lights,
                      r.image.width(), r.image.height());
    rt.image = std::move(r.image);
    row = {{"source", "technique"},
           {"technique", run.spec.name},
           {"family", rt.family},
           {"label", run.spec.label},
           {"parameters", toJson(run.technique->values().settings())},
           {"timings", toJson(r.stats.timings)},
           {"lights", lights}};
    return rt;
}

// A renderer's image (compare --image), read and validated before any work starts.
struct ImageRun {
    ImageSpec spec;
    VisibilityImage image;
};

// What the renderer drew, as the metrics take a technique's render: the oracle's geometry channels
// (the renderer drew the same view: no pixel can be on a different surface) and its V per light.
ChannelImage asRasterImage(const ImageRun& run, const ChannelImage& oracle,
                           const std::vector<Light>& lights) {
    ChannelImage img(oracle.width(), oracle.height());
    for (const char* c :
         {channels::kHit, channels::kPX, channels::kPY, channels::kPZ, channels::kNX, channels::kNY,
          channels::kNZ, channels::kDepth, channels::kMeshId, channels::kPrimId})
        std::copy_n(oracle.channel(c), oracle.pixelCount(), img.addChannel(c));
    for (size_t li = 0; li < lights.size(); ++li)
        std::copy(run.image.v[li].begin(), run.image.v[li].end(),
                  img.addChannel(channels::lightChannel(lights[li].name, channels::kVisibility)));
    return img;
}

// The cost file's figures (absent ones stay unknown); frame_ms is also the camera-free frame.
TechniqueCost imageCost(const ImageRun& run, double oracleSeconds) {
    TechniqueCost cost;
    cost.quartiles = false;
    cost.oracleSeconds = oracleSeconds;
    if (!run.image.cost) return cost;
    const ExternalCost& c = *run.image.cost;
    const auto timing = [](std::optional<double> ms) {
        return ms ? std::optional(TimingStats{*ms, *ms, *ms}) : std::nullopt;
    };
    cost.frameMs = timing(c.frameMs);
    cost.shadowMapMs = timing(c.shadowMs);
    cost.memoryBytes = c.memoryBytes;
    return cost;
}

// One image measured against the oracle per light, as compareTechnique does for a render.
ReportTechnique compareImage(CompareJob& job, const ImageRun& run, nlohmann::json& row) {
    const fs::path dir = job.out / run.spec.fileLabel;
    std::error_code ec;
    fs::create_directories(dir, ec);
    ChannelImage image = asRasterImage(run, job.oracle.image, job.scene.lights);
    const std::string renderer = run.image.cost ? run.image.cost->renderer : "";
    const nlohmann::json params =
        run.image.cost ? run.image.cost->params : nlohmann::json::object();
    if (job.options.writeImages)
        writeExr(
            (dir / "raster.exr").string(), image,
            {{"shadowOracle/technique", run.spec.label}, {"shadowOracle/image", run.spec.path}});
    writeJsonFile(dir / "raster.json", {{"source", "external"},
                                        {"image", run.spec.path},
                                        {"renderer", renderer},
                                        {"params", params}});
    job.metricOptions.filteredTechnique = false;
    ReportTechnique rt;
    rt.label = run.spec.label;
    rt.family = "external";
    rt.curve = "external " + run.spec.label;  // no quality parameter: a point of its own
    rt.fileLabel = run.spec.fileLabel;
    rt.parameters = renderer.empty() ? "image " + run.spec.path : renderer;
    for (const auto& [key, value] : params.items()) rt.parameters += " " + key + "=" + value.dump();
    std::vector<std::pair<std::string, nlohmann::json>> csvParams;
    for (const auto& [key, value] : params.items()) csvParams.emplace_back(key, value);
    nlohmann::json lights = nlohmann::json::object();
    for (size_t li = 0; li < job.scene.lights.size(); ++li) {
        LightComparison lc;
        lc.light = job.scene.lights[li].name;
        lc.metrics =
            computeLightMetrics(job.oracle.image, image, lc.light, job.metricOptions, &lc.maps);
        lc.cost = imageCost(run, job.oracle.stats.lights[li].seconds());
        if (lc.metrics.penumbraMae)
            lc.cost.oracleMsAtEqualError =
                oracleMsAtError(job.oracleCurves[li], *lc.metrics.penumbraMae);
        lights[lc.light] = lc.toJson();
        writeCsvRows(job, "external", run.spec.label, csvParams, lc.light, lights[lc.light]);
        rt.lights.push_back(std::move(lc));
    }
    if (job.options.writeImages)
        writeErrorExr(job.out / ("error_" + run.spec.fileLabel + ".exr"), rt.lights, image.width(),
                      image.height());
    rt.image = std::move(image);
    row = {{"source", "external"},    {"technique", "external"}, {"family", "external"},
           {"label", run.spec.label}, {"image", run.spec.path},  {"renderer", renderer},
           {"parameters", params},    {"timings", nullptr},      {"lights", lights}};
    return rt;
}

// Every technique rendered, its frames interleaved with the others' (renderer.h), and compared as
// soon as its group is done.
void renderAll(CompareJob& job, const std::vector<TechniqueRun>& runs, ReportInput& report,
               nlohmann::json& results) {
    std::vector<const Technique*> techniques;
    for (const TechniqueRun& run : runs) techniques.push_back(run.technique.get());
    report.techniques.resize(runs.size());
    results = nlohmann::json::array();
    for (size_t i = 0; i < runs.size(); ++i) results.push_back(nullptr);
    const auto groupStarts = [&](const std::vector<size_t>& group) {
        std::cerr << "rendering";
        for (size_t i : group) std::cerr << (i == group.front() ? " " : ", ") << runs[i].spec.label;
        std::cerr << (group.size() > 1 ? " (frames interleaved)" : "") << "\n";
    };
    const auto done = [&](size_t i, RasterResult&& r) {
        report.techniques[i] = compareTechnique(job, i, runs[i], std::move(r), results[i]);
    };
    renderInterleaved(job.scene, techniques, job.options.raster, *job.gl, {groupStarts, done});
}

nlohmann::json metricsJson(const CompareJob& job, const nlohmann::json& results) {
    const Scene& scene = job.scene;
    nlohmann::json options = {{"boundary_radius_px", job.options.boundaryRadius},
                              {"contact_threshold", job.metricOptions.contactThreshold}};
    if (job.path) options["frames_path"] = job.path->frames;
    return {
        {"schema_version", kMetricsSchemaVersion},
        {"tool", toolJson()},
        {"scene",
         {{"file", job.options.scenePath},
          {"hash", scene.contentHash},
          {"extent", scene.wsBounds.extent()},
          {"effects", scene.effects}}},
        {"options", options},
        {"oracle",
         {{"cached", job.oracle.fromCache},
          {"key", job.oracle.key},
          {"stats", toJson(job.oracle.stats)}}},
        {"gl", job.gl ? toJson(GlInfo{job.gl->renderer(), job.gl->version(), job.gl->platform()})
                      : nlohmann::json(nullptr)},
        {"results", results}};
}

// --verify: the oracle re-traced independently (docs/oracle.md#verification); a ground truth that
// disagrees with it must not pass silently, cached or not.
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

// Techniques and images as the user named them, each created or read (so validated) before any
// work starts; a label used twice is refused, since rows are told apart by it.
std::vector<TechniqueRun> createTechniques(const CompareOptions& options) {
    std::vector<TechniqueRun> runs;
    for (const std::string& s : options.techniques) {
        TechniqueSpec spec = parseTechniqueSpec(s);
        std::unique_ptr<Technique> technique = createTechnique(spec.name, spec.settings);
        runs.push_back({std::move(spec), std::move(technique)});
    }
    return runs;
}

std::vector<ImageSpec> parseImages(const CompareOptions& options,
                                   const std::vector<TechniqueRun>& runs) {
    if (runs.empty() && options.images.empty())
        throwInputError("command line", "--technique",
                        "nothing to compare: give --technique NAME or --image LABEL=PATH");
    std::set<std::string> labels, fileLabels;
    for (const TechniqueRun& r : runs) fileLabels.insert(r.spec.fileLabel);
    for (const ImageSpec& spec : options.images)
        if (!labels.insert(spec.label).second || !fileLabels.insert(spec.fileLabel).second)
            throwInputError("command line", "--image",
                            "label \"" + printable(spec.label, 60) +
                                "\" is used twice (or names the same folder as another row)");
    const std::vector<ImageSpec>& specs = options.images;
    if (!options.pointsPath.empty()) {
        if (!runs.empty())
            throwInputError("command line", "--points",
                            "judges images only: the built-in techniques render the scene's "
                            "camera, not the G-buffer's pixels (drop --technique)");
        if (options.raster.width > 0 || options.raster.height > 0)
            throwInputError("command line", "--points",
                            "the image is the G-buffer's size: drop --width and --height");
    }
    if (options.pathFrames > 0 && !specs.empty())
        throwInputError("command line", "--frames-path",
                        "an image is one frame: --frames-path works with --technique only");
    return specs;
}

// The oracle: at the G-buffer's points (never cached: the cache is keyed by a camera), or from the
// cache when the same scene content and options were traced before.
CachedOracle oracleFor(const CompareOptions& options, const Scene& scene,
                       const OracleOptions& oracleOptions, const GBuffer* points) {
    if (!points) return traceOrLoad(scene, oracleOptions, {options.cacheDir, options.useCache});
    OracleResult r = runOracleAtPoints(scene, *points, oracleOptions);
    return {std::move(r.image), std::move(r.stats), false, "points " + points->path};
}

// --frames-path: every technique along the scene's camera path (compare_path.h).
void measureFlicker(CompareJob& job, const std::vector<TechniqueRun>& runs,
                    const OracleOptions& oracleOptions, ReportInput& report) {
    std::vector<const Technique*> techniques;
    std::vector<std::string> labels;
    for (const TechniqueRun& run : runs) {
        techniques.push_back(run.technique.get());
        labels.push_back(run.spec.label);
    }
    const CompareOptions& o = job.options;
    job.path = measurePathFlicker(job.scene, techniques, labels, oracleOptions,
                                  {o.cacheDir, o.useCache}, o.raster, *job.gl, o.pathFrames);
    report.pathFrames = o.pathFrames;
    report.flickerStrips = std::move(job.path->strips);
}

// Who measured the report's times: the GL renderer for the techniques, and for images the
// renderers their cost files name.
std::string timedOn(const CompareJob& job, const std::vector<ImageRun>& images) {
    std::vector<std::string> renderers;
    for (const ImageRun& run : images) {
        const std::string name = run.image.cost ? run.image.cost->renderer : "";
        if (!name.empty() && std::find(renderers.begin(), renderers.end(), name) == renderers.end())
            renderers.push_back(name);
    }
    std::string own;
    for (const std::string& name : renderers) own += (own.empty() ? "" : ", ") + name;
    const std::string gl = job.gl ? job.gl->renderer() : "";
    if (images.empty()) return gl;
    if (own.empty()) return gl.empty() ? "none: the images have no cost files" : gl;
    return gl.empty() ? own + " (the images' cost files)" : gl + "; the images by " + own;
}

void writeReportFile(const CompareJob& job, ReportInput& report, const nlohmann::json& metrics,
                     const OracleOptions& oracleOptions, const std::vector<ImageRun>& images) {
    report.oracle = job.oracle.image;
    report.timedOn = timedOn(job, images);
    report.oracleCurves = job.oracleCurves;
    report.embedImages = job.options.embedImages;
    report.provenance = provenance(metrics, job.oracle, oracleOptions);
    writeReport((job.out / "report.html").string(), report);
}

}  // namespace

int runCompareCommand(const CompareOptions& options, nlohmann::json* metricsOut) {
    // Everything the user can get wrong is checked before any work starts.
    std::vector<TechniqueRun> runs = createTechniques(options);
    const std::vector<ImageSpec> imageSpecs = parseImages(options, runs);
    const Scene scene = loadScene(options.scenePath);
    printSceneWarnings(options.scenePath, scene);
    if (options.pathFrames > 0 && !scene.cameraPath)
        throwInputError(options.scenePath, "camera_path",
                        "missing: --frames-path needs the scene's camera path (scene_format 2, "
                        "docs/scene-format.md)");
    // Degenerate interpolated poses are input errors too: found before any work.
    if (options.pathFrames > 0)
        sampleCameraPath(*scene.cameraPath, scene.camera, options.pathFrames);
    OracleOptions oracleOptions = options.oracle;
    if (options.raster.width > 0) oracleOptions.width = options.raster.width;
    if (options.raster.height > 0) oracleOptions.height = options.raster.height;
    std::optional<GBuffer> points;
    if (!options.pointsPath.empty()) points = readGBuffer(options.pointsPath);
    const CameraDesc camera = effectiveCamera(scene, oracleOptions);
    const int width = points ? points->width : camera.width,
              height = points ? points->height : camera.height;
    std::vector<ImageRun> images;
    for (const ImageSpec& spec : imageSpecs)
        images.push_back({spec, readVisibilityImage(spec.path, scene.lights, width, height,
                                                    options.imageEncoding)});
    const fs::path out = makeOutputDir(options.outDir);

    const CachedOracle oracle =
        oracleFor(options, scene, oracleOptions, points ? &*points : nullptr);
    if (options.writeReport)
        writeExr((out / "oracle.exr").string(), oracle.image,
                 {{"shadowOracle/sceneHash", scene.contentHash}});

    // GL only where something renders: images alone are judged without it.
    std::optional<GlContext> gl;
    if (!runs.empty()) gl.emplace();
    CompareJob job{
        options, scene, oracle, gl ? &*gl : nullptr, {}, out, std::ofstream(out / "metrics.csv"),
        {},      {},    {}};
    for (const OracleLightStats& l : oracle.stats.lights)
        job.oracleCurves.push_back(oraclePenumbraCurve(l));
    job.metricOptions.boundaryRadius = options.boundaryRadius;
    job.metricOptions.contactThreshold = options.contactThresholdRelative * scene.wsBounds.extent();
    job.csv << "scene,light,technique,label,metric,value\n";
    ReportInput report;
    report.sceneFile = options.scenePath;
    for (const Light& l : scene.lights) report.lights.push_back(l.name);
    if (options.pathFrames > 0) measureFlicker(job, runs, oracleOptions, report);
    nlohmann::json results = nlohmann::json::array();
    if (!runs.empty()) renderAll(job, runs, report, results);
    for (const ImageRun& image : images) {
        results.push_back(nullptr);
        report.techniques.push_back(compareImage(job, image, results.back()));
    }

    const nlohmann::json metrics = metricsJson(job, results);
    writeJsonFile(out / "metrics.json", metrics);
    job.wide.write(out / "metrics_wide.csv");
    if (options.writeReport) writeReportFile(job, report, metrics, oracleOptions, images);
    std::cout << "compared " << options.scenePath << ": " << runs.size() << " techniques, "
              << images.size() << " images, oracle "
              << (points             ? "at the G-buffer's points"
                  : oracle.fromCache ? "from the cache"
                                     : "traced")
              << "\n  " << (out / "metrics.json").string() << "\n  "
              << (out / "metrics.csv").string() << "\n  " << (out / "metrics_wide.csv").string()
              << "\n";
    if (metricsOut) *metricsOut = metrics;
    return verifyExitCode(options, oracle.stats);
}

}  // namespace so
