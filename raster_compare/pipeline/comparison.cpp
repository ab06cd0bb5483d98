#include "raster_compare/pipeline/comparison.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "core/camera_path.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "core/tool_info.h"
#include "raster_compare/compare/tradeoff.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/pipeline/row_parameters.h"

namespace so {

std::string fileLabelOf(const std::string& label) {
    std::string out;
    for (char c : label) out += (std::isalnum((unsigned char)c) || c == '-' || c == '.') ? c : '_';
    return out;
}

TechniqueSpec parseTechniqueSpec(const std::string& spec) {
    TechniqueSpec t;
    t.label = spec;
    const auto colon = spec.find(':');
    t.name = spec.substr(0, colon);
    if (t.name.empty())
        throwInputError("technique", "", "empty technique name in \"" + printable(spec, 60) + "\"");
    if (colon != std::string::npos) {
        const std::string rest = spec.substr(colon + 1);
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

void checkTechniquesAtPoints(bool atPoints, size_t techniques, const std::string& file,
                             const std::string& field, const std::string& techniqueName) {
    if (atPoints && techniques > 0)
        throwInputError(file, field,
                        "judges images only: the built-in techniques render the scene's camera, "
                        "not a G-buffer's points (drop " +
                            techniqueName + ")");
}

void checkRowLabels(const std::vector<TechniqueSpec>& techniques,
                    const std::vector<ImageSpec>& images) {
    std::set<std::string> labels, fileLabels;
    for (const TechniqueSpec& spec : techniques) fileLabels.insert(spec.fileLabel);
    for (const ImageSpec& spec : images)
        if (!labels.insert(spec.label).second || !fileLabels.insert(spec.fileLabel).second)
            throwInputError("image", "label",
                            "label \"" + printable(spec.label, 60) +
                                "\" is used twice (or names the same folder as another row)");
}

namespace {

// A technique as the user asked for it, created (and so validated) before any work starts.
struct TechniqueRun {
    TechniqueSpec spec;
    std::unique_ptr<Technique> technique;
};

// Everything one comparison shares between its rows.
struct Job {
    const Scene& scene;
    const CachedOracle& oracle;
    MetricOptions metricOptions;
    const std::vector<std::vector<std::pair<double, double>>>& oracleCurves;
    const PathFlicker* path;
    const SequenceResult* sequence;
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
    // A bake (lightmaps) is not a frame: apart from frame_ms.
    cost.bakeMs = stats.lights[li].bakeMs;
    if (stats.lights[li].work) cost.work = stats.lights[li].work->counts;
    cost.oracleSeconds = oracleSeconds;  // what the ground truth cost, so every row has both
    return cost;
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

// Where the exact pass gave some of the light's pixels their V: its cost with the sampled pass
// that found them (the exact pass needs it, unless every pixel is asked for; it ran either way).
std::optional<OracleExactPoint> oracleExactPoint(const OracleLightStats& l) {
    if (!l.area || !l.area->exact || l.area->exact->pixelsExact == 0) return std::nullopt;
    const ExactPenumbraStats& e = *l.area->exact;
    return OracleExactPoint{1e3 * (l.area->seconds + e.seconds), 1e3 * e.seconds, e.pixelsExact};
}

// The shortest form that reads back as the same double: 0.1, not 0.10000000000000001.
std::string shortest(double value) {
    char text[32];
    for (int digits = 15; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, value);
        if (std::strtod(text, nullptr) == value) break;
    }
    return text;
}

// The curve key and quality value of a setting (TradeoffPoint): the name and every parameter but
// the quality one.
void describeCurve(ReportTechnique& rt, const TechniqueRun& run) {
    const ParamSpec* q = qualityParam(findTechnique(run.spec.name).params);
    rt.curve = run.spec.name;
    for (const auto& [key, value] : run.technique->values().all()) {
        if (q && key == q->name)
            rt.quality = value;
        else
            rt.curve += " " + key + "=" + shortest(value);
    }
}

// Every parameter as the report shows it, "k=v ..." from the typed row: a method by its name
// ("contact=on"), a number to 10 significant digits.
std::string parametersText(const RowParameters& parameters) {
    std::string text;
    for (const auto& [key, value] : parameters) {
        char number[48];
        std::snprintf(number, sizeof number, "%.10g", value.number);
        text += (text.empty() ? "" : " ") + key + "=" +
                (value.kind == ParamValue::Kind::Name ? value.name : std::string(number));
    }
    return text;
}

// The row as metrics.json holds it, read back (result_row.h) with its parameters typed by the
// technique's table (row_parameters.h): what the report reads.
ResultRow typedRow(const ComparedRow& row) {
    ResultRow r = readResultRow(rowJson(row), JsonReader("metrics.json"), "results");
    r.parameters = typedParameters(row.technique, row.parameters);
    return r;
}

// Every light of one row measured against the oracle.
void measureLights(const Job& job, ReportTechnique& rt, const ChannelImage& image,
                   const std::function<TechniqueCost(size_t li, double oracleSeconds)>& costOf,
                   const std::vector<TemporalFlicker>* temporal,
                   const std::vector<SequenceMetrics>* sequence) {
    for (size_t li = 0; li < job.scene.lights.size(); ++li) {
        LightComparison lc;
        lc.light = job.scene.lights[li].name;
        // In a sequence the last frame's ghosting is classed where its truth just changed.
        MetricOptions options = job.metricOptions;
        if (sequence && (*sequence)[li].lastTruthChanged.size() == image.pixelCount())
            options.truthChanged = &(*sequence)[li].lastTruthChanged;
        lc.metrics = computeLightMetrics(job.oracle.image, image, lc.light, options, &lc.maps);
        lc.cost = costOf(li, job.oracle.stats.lights[li].seconds());
        if (temporal) lc.temporal = (*temporal)[li];
        if (sequence) lc.sequence = (*sequence)[li];
        if (lc.metrics.penumbraMae)
            lc.cost.oracleMsAtEqualError =
                oracleMsAtError(job.oracleCurves[li], *lc.metrics.penumbraMae);
        rt.lights.push_back(std::move(lc));
    }
}

ComparedRow compareTechnique(Job job, size_t index, const TechniqueRun& run, RasterResult&& r) {
    ComparedRow row;
    row.source = "technique";
    row.technique = run.spec.name;
    row.parameters = toJson(run.technique->values().settings());
    row.provenance = provenanceParts(*run.technique);
    // Built over the sequence's (or the convergence's) frames, else a cold start (one frame holds
    // no history: 0, as raster.json's history_frames).
    if (run.technique->buildsOverFrames())
        row.historyFrames = job.sequence && job.sequence->frames > 1 ? job.sequence->frames : 0;
    ReportTechnique& rt = row.report;
    rt.row.label = run.spec.label;
    rt.row.family = findTechnique(run.spec.name).family;
    rt.row.technique = run.spec.name;
    rt.fileLabel = run.spec.fileLabel;
    describeCurve(rt, run);
    job.metricOptions.filteredTechnique = run.technique->filtered();
    job.metricOptions.comparesDepth = familyComparesDepth(rt.row.family);
    measureLights(
        job, rt, r.image,
        [&](size_t li, double oracleSeconds) { return techniqueCost(r.stats, li, oracleSeconds); },
        job.path ? &job.path->flicker[index] : nullptr,
        job.sequence ? &job.sequence->metrics[index] : nullptr);
    rt.image = std::move(r.image);
    row.stats = std::move(r.stats);
    rt.row = typedRow(row);
    rt.parameters = parametersText(rt.row.parameters);
    return row;
}

// What the renderer drew, as the metrics take a technique's render: the oracle's geometry channels
// (the renderer drew the same view: no pixel can be on a different surface) and its V per light.
ChannelImage asRasterImage(const ImageInput& in, const ChannelImage& oracle,
                           const std::vector<Light>& lights) {
    ChannelImage img(oracle.width(), oracle.height());
    for (const char* c :
         {channels::kHit, channels::kPX, channels::kPY, channels::kPZ, channels::kNX, channels::kNY,
          channels::kNZ, channels::kDepth, channels::kMeshId, channels::kPrimId})
        std::copy_n(oracle.channel(c), oracle.pixelCount(), img.addChannel(c));
    for (size_t li = 0; li < lights.size(); ++li)
        std::copy(in.image.v[li].begin(), in.image.v[li].end(),
                  img.addChannel(channels::lightChannel(lights[li].name, channels::kVisibility)));
    return img;
}

// The cost file's figures (absent ones stay unknown); frame_ms is also the camera-free frame.
TechniqueCost imageCost(const ImageInput& in, double oracleSeconds) {
    TechniqueCost cost;
    cost.quartiles = false;
    cost.oracleSeconds = oracleSeconds;
    if (!in.image.cost) return cost;
    const ExternalCost& c = *in.image.cost;
    const auto timing = [](std::optional<double> ms) {
        return ms ? std::optional(TimingStats{*ms, *ms, *ms}) : std::nullopt;
    };
    cost.frameMs = timing(c.frameMs);
    cost.shadowMapMs = timing(c.shadowMs);
    cost.memoryBytes = c.memoryBytes;
    return cost;
}

ComparedRow compareImage(Job job, const ImageInput& in) {
    ComparedRow row;
    row.source = "external";
    row.technique = "external";
    row.imagePath = in.spec.path;
    row.renderer = in.image.cost ? in.image.cost->renderer : "";
    row.parameters = in.image.cost ? in.image.cost->params : nlohmann::json::object();
    ReportTechnique& rt = row.report;
    rt.row.label = in.spec.label;
    rt.row.family = "external";
    rt.row.technique = "external";
    rt.curve = "external " + in.spec.label;  // no quality parameter: a point of its own
    rt.fileLabel = in.spec.fileLabel;
    rt.parameters = row.renderer.empty() ? "image " + in.spec.path : row.renderer;
    for (const auto& [key, value] : row.parameters.items())
        rt.parameters += " " + key + "=" + value.dump();
    ChannelImage image = asRasterImage(in, job.oracle.image, job.scene.lights);
    job.metricOptions.filteredTechnique = false;
    measureLights(
        job, rt, image, [&](size_t, double oracleSeconds) { return imageCost(in, oracleSeconds); },
        nullptr, nullptr);
    rt.image = std::move(image);
    rt.row = typedRow(row);
    return row;
}

// compare --converge N: the scene standing still for N frames, as measureSequence takes a scene
// that moves: a Sequence of N frames with nothing on its clock (no animated mesh, no light or
// camera path), so that every frame poses the same scene (sceneAtTime returns it unchanged, its
// oracle cached once) and only the frame index turns the techniques' jittered taps.
Scene stillSequence(const Scene& scene, int frames) {
    Scene still = scene;
    still.sequence = Sequence{frames, 1.0, ""};
    still.cameraPath.reset();
    still.lightPaths.clear();
    for (MeshPrimitive& mesh : still.meshes) mesh.animation.reset();
    return still;
}

// The sequence's frames reported as the convergence's ("converge frames", the CLI's
// "converge: frame k of N").
ProgressCallback convergeProgress(const ProgressCallback& progress) {
    if (!progress) return progress;
    return [progress](const ProgressUpdate& u) {
        static const std::string kStage = "converge frames";
        return u.stage == "sequence frames" ? progress({kStage, u.done, u.total}) : progress(u);
    };
}

// compare --sequence (the scene's own frames) or --converge N (N still frames of `scene`): every
// technique over the frames, each row then judging the last.
SequenceResult measureFrames(const Scene& scene, const CachedOracle& oracle,
                             const std::vector<TechniqueRun>& runs,
                             const ComparisonOptions& options, const MetricOptions& metricOptions,
                             const GlContext& gl) {
    std::vector<const Technique*> list;
    for (const TechniqueRun& run : runs) list.push_back(run.technique.get());
    // The comparison's oracle is the last frame's where it was traced as the frames are: not
    // at a G-buffer's points, and with the posed scene's own camera.
    const bool sameAsLast = !oracle.atPoints && !options.pathOracle.camera;
    const ChannelImage* last = sameAsLast ? &oracle.image : nullptr;
    if (options.sequence)
        return measureSequence(*options.sequence, list, options.pathOracle, options.pathCache,
                               options.raster, metricOptions, gl, options.progress, last);
    return measureSequence(stillSequence(scene, options.convergeFrames), list, options.pathOracle,
                           options.pathCache, options.raster, metricOptions, gl,
                           convergeProgress(options.progress), last);
}

// Techniques created (so validated) and labels checked (checkRowLabels) before any work starts.
std::vector<TechniqueRun> createTechniques(const std::vector<TechniqueSpec>& specs,
                                           const std::vector<ImageInput>& images) {
    if (specs.empty() && images.empty())
        throwInputError("comparison", "", "nothing to compare: no technique and no image");
    std::vector<TechniqueRun> runs;
    for (const TechniqueSpec& spec : specs)
        runs.push_back({spec, createTechnique(spec.name, spec.settings)});
    std::vector<ImageSpec> imageSpecs;
    for (const ImageInput& in : images) imageSpecs.push_back(in.spec);
    checkRowLabels(specs, imageSpecs);
    return runs;
}

// The settings' notices of a parameter's former name (ParamValues::deprecations), once each.
std::vector<std::string> deprecationsOf(const std::vector<TechniqueRun>& runs) {
    std::vector<std::string> notices;
    for (const TechniqueRun& run : runs)
        for (const std::string& notice : run.technique->values().deprecations())
            notices.push_back(notice);
    return notices;
}

void checkImages(const std::vector<ImageInput>& images, const Scene& scene,
                 const ChannelImage& oracle) {
    const size_t pixels = oracle.pixelCount();
    for (const ImageInput& in : images) {
        bool fits = in.image.v.size() == scene.lights.size();
        for (const std::vector<float>& v : in.image.v) fits = fits && v.size() == pixels;
        if (!fits)
            throwInputError(in.spec.path, in.spec.label,
                            "not one plane of " + std::to_string(oracle.width()) + " x " +
                                std::to_string(oracle.height()) + " per light of the scene (" +
                                std::to_string(scene.lights.size()) + ")");
    }
}

// Every technique rendered, its frames interleaved with the others' (renderer.h), and measured as
// soon as its group is done.
void renderAll(const Job& job, const std::vector<TechniqueRun>& runs,
               const ComparisonOptions& options, const GlContext& gl,
               std::vector<ComparedRow>& rows) {
    std::vector<const Technique*> techniques;
    for (const TechniqueRun& run : runs) techniques.push_back(run.technique.get());
    rows.resize(runs.size());
    const auto groupStarts = [&](const std::vector<size_t>& group) {
        if (!options.renderingGroup) return;
        std::vector<std::string> labels;
        for (size_t i : group) labels.push_back(runs[i].spec.label);
        options.renderingGroup(labels);
    };
    Progress progress("techniques", runs.size(), options.progress);
    const auto done = [&](size_t i, RasterResult&& r) {
        rows[i] = compareTechnique(job, i, runs[i], std::move(r));
        progress.advance(1);
    };
    // In a sequence (or still frames) the rows judge its last frame as the sequence rendered it,
    // timed and counted with the history the frames before built: nothing is rendered again.
    if (job.sequence) {
        for (size_t i = 0; i < runs.size(); ++i)
            done(i, {job.sequence->lastImages[i], job.sequence->lastStats[i]});
        return;
    }
    renderInterleaved(job.scene, techniques, options.raster, gl, {groupStarts, done});
}

}  // namespace

Comparison compareWithOracle(const Scene& scene, const CachedOracle& oracle,
                             const std::vector<TechniqueSpec>& techniques,
                             const std::vector<ImageInput>& images,
                             const ComparisonOptions& options, GlContext* gl) {
    const std::vector<TechniqueRun> runs = createTechniques(techniques, images);
    checkImages(images, scene, oracle.image);
    if (options.pathFrames > 0) {
        if (!images.empty())
            throwInputError("comparison", "frames",
                            "an image is one frame: camera path frames take techniques only");
        if (!scene.cameraPath)
            throwInputError(scene.path.string(), "camera_path",
                            "missing: frames along the camera path need one (scene_format 2, "
                            "docs/scene-format.md)");
        // Degenerate interpolated poses are input errors too: found before any work.
        sampleCameraPath(*scene.cameraPath, scene.camera, options.pathFrames);
    }
    if (options.convergeFrames > 0 &&
        (!images.empty() || options.pathFrames > 0 || options.sequence))
        throwInputError("comparison", "converge",
                        "still frames are judged with techniques only (no images, no camera path "
                        "frames, no sequence)");
    if (options.sequence) {
        if (!images.empty() || options.pathFrames > 0)
            throwInputError("comparison", "sequence",
                            "a sequence is judged with techniques only (no images, no camera "
                            "path frames)");
        if (!options.sequence->sequence)
            throwInputError(options.sequence->path.string(), "sequence",
                            "missing: judging a sequence needs one (scene_format 5, "
                            "docs/scene-format.md)");
    }
    std::optional<GlContext> ownGl;
    if (!runs.empty() && !gl) gl = &ownGl.emplace();

    Comparison out;
    for (const OracleLightStats& l : oracle.stats.lights) {
        out.oracleCurves.push_back(oraclePenumbraCurve(l));
        out.oracleExact.push_back(oracleExactPoint(l));
    }
    out.metricOptions.boundaryRadius = options.boundaryRadius;
    out.metricOptions.contactThreshold = options.contactThresholdRelative * scene.wsBounds.extent();
    if (gl) out.gl = GlInfo{gl->renderer(), gl->version(), gl->platform()};
    if (options.pathFrames > 0) {
        std::vector<const Technique*> list;
        std::vector<std::string> labels;
        for (const TechniqueRun& run : runs) {
            list.push_back(run.technique.get());
            labels.push_back(run.spec.label);
        }
        out.path = measurePathFlicker(scene, list, labels, options.pathOracle, options.pathCache,
                                      options.raster, *gl, options.pathFrames, options.progress);
    }
    if (options.sequence || options.convergeFrames > 0) {
        out.sequence = measureFrames(scene, oracle, runs, options, out.metricOptions, *gl);
        out.convergeFrames = options.convergeFrames;
    }
    const Job job{scene,
                  oracle,
                  out.metricOptions,
                  out.oracleCurves,
                  out.path ? &*out.path : nullptr,
                  out.sequence ? &*out.sequence : nullptr};
    if (!runs.empty()) renderAll(job, runs, options, *gl, out.rows);
    for (const ImageInput& in : images) out.rows.push_back(compareImage(job, in));
    if (out.path) out.warnings = out.path->warnings;
    if (out.sequence) out.warnings = out.sequence->warnings;
    const std::vector<std::string> deprecations = deprecationsOf(runs);  // said first
    out.warnings.insert(out.warnings.begin(), deprecations.begin(), deprecations.end());
    if (gl)
        for (std::string& w : gl->takeWarnings()) out.warnings.push_back(std::move(w));
    return out;
}

nlohmann::json rowJson(const ComparedRow& row) {
    nlohmann::json lights = nlohmann::json::object();
    for (const LightComparison& lc : row.report.lights) lights[lc.light] = lc.toJson();
    if (row.source == "external")
        return {
            {"source", "external"},          {"technique", "external"}, {"family", "external"},
            {"label", row.report.row.label}, {"image", row.imagePath},  {"renderer", row.renderer},
            {"parameters", row.parameters},  {"timings", nullptr},      {"lights", lights}};
    nlohmann::json parts = nlohmann::json::array();
    for (const ProvenancePart& p : row.provenance) {
        nlohmann::json part = {{"of", p.of},
                               {"anchor", p.provenance.anchor},
                               {"fidelity", fidelityName(p.provenance.fidelity)}};
        if (p.provenance.fidelity == Fidelity::Variant)
            part["deviations"] = p.provenance.deviations;
        parts.push_back(part);
    }
    nlohmann::json j = {
        {"source", "technique"},
        {"technique", row.technique},
        {"family", row.report.row.family},
        {"label", row.report.row.label},
        {"provenance",
         {{"fidelity", fidelityName(combinedFidelity(row.provenance))}, {"parts", parts}}},
        {"parameters", row.parameters},
        {"timings", row.stats ? toJson(row.stats->timings) : nlohmann::json(nullptr)},
        {"lights", lights}};
    if (row.historyFrames) j["history_frames"] = *row.historyFrames;
    return j;
}

nlohmann::json metricsHeaderJson(const Scene& scene, const std::string& sceneFile,
                                 const CachedOracle& oracle, const Comparison& comparison,
                                 int boundaryRadius) {
    nlohmann::json options = {{"boundary_radius_px", boundaryRadius},
                              {"contact_threshold", comparison.metricOptions.contactThreshold}};
    if (comparison.path) options["frames_path"] = comparison.path->frames;
    if (comparison.sequence)
        options[comparison.convergeFrames > 0 ? "converge_frames" : "sequence_frames"] =
            comparison.sequence->frames;
    return {{"schema_version", kMetricsSchemaVersion},
            {"tool", toolJson()},
            {"scene",
             {{"file", sceneFile},
              {"hash", scene.contentHash},
              {"extent", scene.wsBounds.extent()},
              {"effects", scene.effects}}},
            {"options", options},
            {"oracle",
             {{"cached", oracle.fromCache}, {"key", oracle.key}, {"stats", toJson(oracle.stats)}}},
            {"gl", comparison.gl ? toJson(*comparison.gl) : nlohmann::json(nullptr)}};
}

nlohmann::json metricsJson(const Scene& scene, const std::string& sceneFile,
                           const CachedOracle& oracle, const Comparison& comparison,
                           int boundaryRadius) {
    nlohmann::json metrics =
        metricsHeaderJson(scene, sceneFile, oracle, comparison, boundaryRadius);
    nlohmann::json& results = metrics["results"] = nlohmann::json::array();
    for (const ComparedRow& row : comparison.rows) results.push_back(rowJson(row));
    return metrics;
}

}  // namespace so
