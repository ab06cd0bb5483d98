#include "raster_compare/pipeline/compare_output.h"

#include <algorithm>
#include <ctime>
#include <fstream>

#include "core/error.h"
#include "core/json_file.h"
#include "raster_compare/pipeline/csv_table.h"

namespace so {

namespace fs = std::filesystem;

ChannelImage errorImage(const ReportTechnique& row) {
    ChannelImage errors(row.image.width(), row.image.height());
    for (const LightComparison& lc : row.lights) {
        for (const ArtifactClass& c : kArtifactClasses) {
            const std::vector<float>& plane = lc.maps.of(c.id);
            std::copy(plane.begin(), plane.end(), errors.addChannel(lc.light + "." + c.layer));
        }
        std::copy(lc.maps.error.begin(), lc.maps.error.end(),
                  errors.addChannel(lc.light + "." + kErrorLayer));
    }
    return errors;
}

namespace {

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
            // A technique that builds over frames: how many built the image (0: a cold start).
            if (result.contains("history_frames"))
                cells.emplace_back("history_frames", result["history_frames"].dump());
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

// A row's folder: raster.json always, its image and error EXR unless a sweep task drops them.
void writeRowFiles(const fs::path& out, const ComparedRow& row, bool images) {
    const fs::path dir = out / row.report.fileLabel;
    std::error_code ec;
    fs::create_directories(dir, ec);
    ExrAttributes attributes = {{"shadowOracle/technique", row.report.row.label}};
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
    writeExr((out / ("error_" + row.report.fileLabel + ".exr")).string(), errorImage(row.report));
}

// The report's provenance table: what made it, as a person reads it.
std::vector<std::pair<std::string, std::string>> provenance(const nlohmann::json& metrics,
                                                            const CachedOracle& oracle,
                                                            const AreaSampling& o) {
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    const auto& tool = metrics["tool"];
    const nlohmann::json gl = metrics["gl"].is_object() ? metrics["gl"] : nlohmann::json::object();
    char sampling[160];
    std::snprintf(sampling, sizeof sampling,
                  "target error %g, agreement target %g, max spp %d, fixed spp %d, seed %u",
                  o.targetError, o.agreementTarget, o.maxSpp, o.fixedSpp, o.seed);
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

void writeReportFile(const fs::path& path, const std::string& scenePath, const Scene& scene,
                     const CachedOracle& oracle, Comparison& comparison,
                     const nlohmann::json& metrics, const AreaSampling& sampling,
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
    report.provenance = provenance(metrics, oracle, sampling);
    if (comparison.path) {
        report.pathFrames = comparison.path->frames;
        report.flickerStrips = std::move(comparison.path->strips);
    }
    if (comparison.sequence) report.sequenceFrames = comparison.sequence->frames;
    writeReport(path.string(), report);
}

}  // namespace

CompareOutputFiles writeCompareOutput(const fs::path& dir, const Scene& scene,
                                      const CachedOracle& oracle, Comparison& comparison,
                                      const CompareOutputOptions& options) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throwInputError(dir.string(), "", "cannot create the folder: " + ec.message());
    CompareOutputFiles files{dir / "metrics.json", dir / "metrics.csv", dir / "metrics_wide.csv",
                             std::nullopt};
    if (options.writeReport)
        writeExr((dir / "oracle.exr").string(), oracle.image,
                 {{"shadowOracle/sceneHash", scene.contentHash}});
    for (const ComparedRow& row : comparison.rows) writeRowFiles(dir, row, options.writeImages);
    const nlohmann::json metrics =
        metricsJson(scene, options.scenePath, oracle, comparison, options.boundaryRadius);
    writeJsonFile(files.metricsJson, metrics);
    writeCsvs(dir, options.scenePath, metrics);
    if (options.writeReport) {
        files.report = dir / "report.html";
        writeReportFile(*files.report, options.scenePath, scene, oracle, comparison, metrics,
                        options.sampling, options.embedImages);
    }
    return files;
}

}  // namespace so
