// A comparison as a function: the built-in techniques rendered (raster_compare/gl) and renderers'
// images, each measured against the oracle per light (raster_compare/compare), returned as typed
// rows. No files, no terminal: compareScene (compare_scene.h, what `shadow-oracle compare` and a
// sweep's task run) calls it and compare_output.h writes what it returns; the C++ package and the
// Python module return it. JSON only where a file is made
// (metricsJson, rowJson).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/compare_option_table.h"
#include "core/progress.h"
#include "core/visibility_image.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/compare/report.h"
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/render/raster_result.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/pipeline/path_flicker.h"
#include "raster_compare/pipeline/sequence_compare.h"

namespace so {

class GlContext;

// A technique as asked for: "name[:key=value,...]".
struct TechniqueSpec {
    std::string name;
    std::vector<std::string> settings;  // key=value
    std::string label;                  // "name" or "name:k=v,k=v", as given
    std::string fileLabel;              // the label made safe for file names
};
// Throws InputError (file "technique", the spec as field) on an empty name.
TechniqueSpec parseTechniqueSpec(const std::string& spec);

// A renderer's image judged like a technique (docs/external.md, "Images in").
struct ImageSpec {
    std::string label;      // the row's label, as given
    std::string fileLabel;  // made safe for file names, as TechniqueSpec's
    std::string path;
};
ImageSpec makeImageSpec(const std::string& label, const std::string& path);

// Letters, digits, '-' and '.' kept, anything else '_'.
std::string fileLabelOf(const std::string& label);

// Rows are told apart by their labels: an image's label used twice, or naming the same folder as
// another row's, is an InputError (file "image", field "label"). A technique's label may repeat
// (the same setting twice renders twice).
void checkRowLabels(const std::vector<TechniqueSpec>& techniques,
                    const std::vector<ImageSpec>& images);

// An image read and validated against the scene's lights and the oracle's size
// (readVisibilityImage), or made in memory (a Python array).
struct ImageInput {
    ImageSpec spec;
    VisibilityImage image;
};

// An oracle traced at a G-buffer's points (CachedOracle::atPoints) judges images only: an
// InputError(file, field) when `techniques` > 0, telling to drop `techniqueName` (the caller's name
// of the techniques: "--technique", "techniques"). The one check of that rule, for every caller.
void checkTechniquesAtPoints(bool atPoints, size_t techniques, const std::string& file,
                             const std::string& field, const std::string& techniqueName);

struct ComparisonOptions {
    // The techniques' frames; width and height must be the oracle's (0: the scene camera's).
    RasterOptions raster;
    int boundaryRadius = kDefaultBoundaryRadius;  // r of docs/metrics.md
    double contactThresholdRelative = 0.01;       // of the scene's bounding-box diagonal
    // N >= 2: every technique also along the scene's camera path in N frames, for
    // temporal_flicker_rate, with the oracle of each frame from `pathOracle` and `pathCache`.
    int pathFrames = 0;
    OracleOptions pathOracle;
    OracleCacheOptions pathCache;
    // compare --sequence: the scene with its motion (the `scene` compared is then its last frame,
    // posed): every technique also over the sequence's frames (sequence_compare.h), each frame's
    // oracle from `pathOracle` and `pathCache`; each row's image is the sequence's last frame as
    // judged (its history resolved). Not with pathFrames or images. Null: no sequence.
    const Scene* sequence = nullptr;
    // compare --converge N (>= 1; 0: off): every technique also over N still frames of `scene`
    // (a Sequence with nothing moving, its frame index 0 .. N - 1, sequence_compare.h), each row's
    // image the last of them; `sequence` in Comparison holds their metrics. Not with pathFrames,
    // sequence or images.
    int convergeFrames = 0;
    // Before each group of techniques is rendered together: their labels (the CLI says so).
    std::function<void(const std::vector<std::string>&)> renderingGroup;
    // The camera path's frames ("camera path frames") and the techniques rendered
    // ("techniques"); can cancel between them.
    ProgressCallback progress;
};

// One technique or image against the oracle: a row of metrics.json.
struct ComparedRow {
    std::string source;               // "technique" or "external"
    std::string technique;            // the registered name, or "external"
    std::string imagePath, renderer;  // external rows: the image and its cost file's renderer
    // The settings as metrics.json's "parameters": a technique's every parameter by name, an
    // image's its cost file's params.
    nlohmann::json parameters = nlohmann::json::object();
    std::optional<RasterStats> stats;  // a technique's render: what raster.json holds
    // A technique's: whose designs it grades (technique.h provenanceParts), metrics.json's
    // "provenance"; empty for an image.
    std::vector<ProvenancePart> provenance;
    // A technique that builds over frames (Technique::buildsOverFrames): how many frames built the
    // judged image (metrics.json's "history_frames"): 0 for a single frame (a cold start), the
    // frames of --converge or --sequence; none for every other row.
    std::optional<int> historyFrames;
    // label, family, curve, every light's metrics, costs and error maps, and the image judged.
    ReportTechnique report;
};

struct Comparison {
    std::vector<ComparedRow> rows;  // the techniques in the order given, then the images
    // Per light, sampled area lights only: the oracle's penumbra cost curve (ms, mean stated 95%
    // half-width), which every row's oracle_ms_at_equal_error is read from.
    std::vector<std::vector<std::pair<double, double>>> oracleCurves;
    // Per light: where the oracle's exact penumbra pass gave V, what it cost (the report's chart).
    std::vector<std::optional<OracleExactPoint>> oracleExact;
    MetricOptions metricOptions;  // what the metrics used (the contact threshold in world units)
    std::optional<PathFlicker> path;         // pathFrames > 0
    std::optional<SequenceResult> sequence;  // ComparisonOptions::sequence or convergeFrames
    int convergeFrames = 0;                  // ComparisonOptions::convergeFrames
    std::optional<GlInfo> gl;                // when a technique was rendered
    // The GL driver's and the camera path's oracle cache's warnings, and the techniques'
    // deprecation notices (a parameter's former name), for the caller to print.
    std::vector<std::string> warnings;
};

// Every technique and image checked first (unknown names and parameters, labels used twice, a
// camera path where pathFrames asks for one, images of another size than the oracle's): InputError
// before any work. `gl` may be null: a context is made when a technique needs one (images alone
// need none).
Comparison compareWithOracle(const Scene& scene, const CachedOracle& oracle,
                             const std::vector<TechniqueSpec>& techniques,
                             const std::vector<ImageInput>& images,
                             const ComparisonOptions& options, GlContext* gl = nullptr);

// metrics.json's entry of a row in "results" (docs/metrics.md).
nlohmann::json rowJson(const ComparedRow& row);
// metrics.json but its "results": what made the rows (tool, scene, options, oracle, gl).
nlohmann::json metricsHeaderJson(const Scene& scene, const std::string& sceneFile,
                                 const CachedOracle& oracle, const Comparison& comparison,
                                 int boundaryRadius);
// metrics.json as a whole; `sceneFile` as the user named it.
nlohmann::json metricsJson(const Scene& scene, const std::string& sceneFile,
                           const CachedOracle& oracle, const Comparison& comparison,
                           int boundaryRadius);

}  // namespace so
