// The index page over many compare runs (`shadow-oracle index`): per artifact metric one matrix,
// techniques against scene x light, each cell coloured by its error and linked to the run's
// report. metrics.json is read once into typed rows (result_row.h); the page is written from them,
// so the HTML never looks a key up in JSON. Self-contained: inline CSS, no script, no network.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/compare/result_row.h"

namespace so {

// What the index needs of one metrics.json.
struct SceneMetrics {
    std::string path;       // the metrics.json read, for messages
    std::string sceneFile;  // scene.file, e.g. "scenes/contact_box.scene.json"
    int schemaVersion = 0;
    std::string timedOn;              // gl.renderer, empty when absent
    std::vector<std::string> lights;  // every light of the results, in first-seen order
    // The technique settings, read into typed rows (result_row.h): a label is the row of every
    // matrix; a metric that is null (does not apply there) or absent (an older schema_version)
    // has no cell.
    std::vector<ResultRow> results;
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
