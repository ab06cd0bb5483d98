// The one table of public metrics (docs/metrics.md): every name metrics.json, metrics.csv and the
// limits file use, with its unit, which way is better, where it applies, one sentence of meaning,
// and what the readers of the rows need of it: its label, its built-in tolerance when a baseline
// compares it (baseline.h), and its place among the cost axes the reports plot. The gate validates
// limit keys against it, the baseline takes its metrics, directions and tolerances from it,
// compare's report, the index and the sweep report their labels, meanings, number formats (by the
// unit: formatMetricValue), cost axes and "lower is better", and docs/metrics.md's table is
// generated from it (scripts/update-docs; a test fails when they differ). The reports read
// metrics by these names from typed rows (result_row.h), which metrics.json is read back into.
//
// A new metric is its row here plus its computation. A cost's row holds how to read it from
// TechniqueCost (MetricInfo::cost), which TechniqueCost::toJson writes from this table, so a new
// cost is its row and the field where it is measured; it then reaches metrics.json, the CSVs,
// compare's chart, budget tables and all-metrics table, the sweep's fronts and budget tables and
// the baseline from its row alone: `grep -rln rays_traced raster_compare/compare` finds this table
// only. An error metric is its row, its field and computation in metrics.h/.cpp and its line in
// LightMetrics::toJson (and, where a report should show it, a line in that report's own choice of
// columns: report_tables.cpp, index_page.cpp). A test checks that every name a full row has is
// here and every entry here is in some row.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace so {

struct TechniqueCost;

// Which way a metric gets better.
enum class Better {
    Lower,             // an error, a rate, a distance, a cost
    Higher,            // none of today's metrics; kept so a score can be added without a new rule
    SmallerMagnitude,  // signed: |x| matters (penumbra_bias: < 0 too hard, > 0 too soft)
    None               // describes the view or the run, not the technique (counts, flags)
};

enum class MetricUnit {
    V,            // visibility, 0 to 1
    Share,        // a fraction of some pixels, 0 to 1
    Pixels,       // distances in image pixels
    WorldUnits,   // distances in the scene's units
    Ms,           // milliseconds
    Seconds,      // seconds
    Bytes,        // bytes
    Count,        // a whole number of pixels, pairs, frames or profiles
    Ratio,        // a dimensionless ratio (a texel's footprint over a pixel's)
    Correlation,  // Pearson's r, -1 to 1
    Flag          // true or false
};

// Where a metric has a value; elsewhere it is null (not applicable: the gate counts it so).
enum class MetricScope {
    All,                 // every row
    HardLights,          // point, spot and directional lights (no penumbra)
    AreaLights,          // sampled area lights (the oracle has NAME.stderr)
    FilteredTechniques,  // vsm, esm, evsm
    ScreenSpaceFilter,   // the raster has NAME.V_unfiltered (blur)
    OccluderDistance,    // the oracle has NAME.occ_dist (the contact effect)
    AliasingPrediction,  // the raster has NAME.aliasing_pred
    FramesPath,          // compare --frames-path; absent from the row otherwise
    Sequence,            // compare --sequence; absent from the row otherwise
    BakedTechniques      // techniques that bake before the first frame (lightmap)
};

// What a baseline allows a metric to move (docs/gate.md#baseline), in the metric's unit.
struct Tolerance {
    double abs = 0.0;  // in the metric's unit
    double rel = 0.0;  // of the baseline's |value|
};

// What widens a metric's tolerance by the sampled oracle's stated uncertainty (area lights).
enum class OracleNoise {
    None,           // shares of pixels, pixel distances, costs: the tolerance covers it
    MeanHalfWidth,  // means of V errors: the mean stated 95% half-width over the penumbra
    WorstHalfWidth  // max_abs: the largest stated 95% half-width
};

// Whether and how `gate --baseline` compares a metric (docs/gate.md#baseline).
struct BaselineRule {
    enum Use : unsigned char {
        Never,      // not a quality metric: counts, shares of the view, predictions, the oracle's
        ByDefault,  // compared unless the limits file's baseline.ignore names it
        WhenNamed   // costs: compared only when the limits file's baseline.metrics names it
    } use = Never;
    Tolerance tolerance;  // built-in
    OracleNoise noise = OracleNoise::None;
};

// A cost the reports plot error against (compare's chart and budget tables, the sweep's fronts).
// The axes are shown in this order, each kind in the table's order.
enum class CostAxis : unsigned char {
    None,    // not an axis
    Frame,   // the frame time
    Pass,    // one pass's time: compare's chart only (a sweep plots whole frames)
    Memory,  // GL memory
    Work     // the work of a frame (docs/metrics.md, Work)
};

struct MetricInfo {
    const char* name;  // as in metrics.csv and the limits file: nested names joined by a dot
    MetricUnit unit;
    Better better;
    MetricScope scope;
    const char* description;  // one sentence; docs/metrics.md has the full definitions
    // Its name for people where the reports show it (compare's report, the index, the sweep
    // report: "acne", "frame time"); null: the name itself.
    const char* label = nullptr;
    BaselineRule baseline = {};
    CostAxis costAxis = CostAxis::None;
    // A cost ("cost." names): its value in a row as metrics.json writes it (its JSON type: an
    // integer, a boolean, null where unknown). TechniqueCost::toJson writes every one it has.
    nlohmann::json (*cost)(const TechniqueCost&) = nullptr;
};

// Every public metric, in the order of docs/metrics.md. metrics.json and metrics.csv order their
// names as the JSON objects do (sorted by key at each level), which is a public contract too.
std::span<const MetricInfo> allMetrics();

// The entry of `name` (as in metrics.csv), or null.
const MetricInfo* findMetric(const std::string& name);
// The entry of a name the code itself uses ("cost.frame_ms"); one missing is a bug.
const MetricInfo& metricInfo(const std::string& name);

// A dotted name's first part with members in the table ("penumbra_width_error_px"): metrics.json
// has the object, or null where none of its members applies.
bool isMetricGroup(const std::string& name);

// The table's names nearest to a misspelled one, best first (at most `count`): a group's members,
// else those within a few edits. Empty when nothing is close.
std::vector<std::string> nearestMetrics(const std::string& name, size_t count = 3);

const char* unitName(MetricUnit u);    // "V", "share", "px", "world units", ...
const char* betterName(Better b);      // "lower", "higher", "nearer 0", "none"
const char* scopeName(MetricScope s);  // "all", "hard lights", ...

// How the reports show a metric, from its row: its label, a value formatted for its unit (V to 4
// decimals, or signed to 3 where nearer 0 is better; shares as percentages; pixels to 2 decimals;
// bytes in MiB; counts with k, M, G), and the unit such a value is in ("ms", "MiB", "px",
// "count"; "" where the text says it, as a percentage does, or there is none).
std::string metricLabel(const MetricInfo& m);
std::string formatMetricValue(const MetricInfo& m, double v);
const char* displayUnit(const MetricInfo& m);
// The factor from the metric's unit to displayUnit's: 1 / 2^20 for bytes (MiB), else 1.
double displayScale(const MetricInfo& m);

// The cost axes in the order the reports show them (CostAxis); without the single passes' times
// when `passes` is false.
std::vector<const MetricInfo*> costAxes(bool passes);

// The table as docs/metrics.md shows it, between its metric-table markers.
std::string metricTableMarkdown();

}  // namespace so
