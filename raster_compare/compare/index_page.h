// The index page over many compare runs (`shadow-oracle index`): per artifact metric one matrix,
// techniques against scene x light, each cell coloured by its error and linked to the run's
// report. metrics.json is read once into the plain structs below; the page is written from them,
// so the HTML never looks a key up in JSON. Self-contained: inline CSS, no script, no network.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace so {

// One light of one result: the metrics the index shows, null (none) where metrics.json has null
// (the metric does not apply there, docs/metrics.md) or lacks the key (an older schema_version).
struct IndexLightMetrics {
    std::string light;
    std::optional<double> mae;
    std::optional<double> acneRate;
    std::optional<double> peterPanningRate;
    std::optional<double> boundaryDisplacementP95Px;  // boundary_displacement_px.p95
    std::optional<double> lightBleedingRate;
    std::optional<double> penumbraMae;
    std::optional<double> frameMs;  // cost.frame_ms: median over the timed frames
    // compare --sequence only (docs/metrics.md#sequence): sequence.mae_mean, sequence.lag_mae.
    std::optional<double> sequenceMaeMean, sequenceLagMae;
};

// One technique setting of a compare run.
struct IndexResult {
    std::string label;      // e.g. "pcss:filter_samples=8": the row of the matrices
    std::string technique;  // e.g. "pcss"
    std::string family;     // empty before schema_version 3
    std::vector<IndexLightMetrics> lights;
};

// What the index needs of one metrics.json.
struct SceneMetrics {
    std::string path;       // the metrics.json read, for messages
    std::string sceneFile;  // scene.file, e.g. "scenes/contact_box.scene.json"
    int schemaVersion = 0;
    std::string timedOn;              // gl.renderer, empty when absent
    std::vector<std::string> lights;  // every light of the results, in first-seen order
    std::vector<IndexResult> results;
};

// Throws InputError naming `path` and the field (e.g. "results[2].lights.key.mae") on anything
// that is not a metrics.json of schema_version 1 to kMetricsSchemaVersion.
SceneMetrics parseSceneMetrics(const nlohmann::json& metrics, const std::string& path);
// Reads and parses the file; InputError when it cannot be read or is not JSON.
SceneMetrics readSceneMetrics(const std::string& path);

// "scenes/contact_box.scene.json" -> "contact_box": the column header of the index.
std::string sceneStem(const std::string& sceneFile);

struct IndexEntry {
    SceneMetrics metrics;
    std::string reportHref;  // relative to the index page, e.g. "contact_box/report.html"
};

// The artifact metrics that get a matrix, in page order, by their metrics.json names.
const std::vector<std::string>& indexMetricNames();

// The whole page. Matrices whose cells are all empty are left out.
std::string indexPageHtml(const std::vector<IndexEntry>& entries);
// Writes it; InputError naming the file when it cannot be written.
void writeIndexPage(const std::string& path, const std::vector<IndexEntry>& entries);

}  // namespace so
