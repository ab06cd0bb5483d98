// The gate against a baseline (docs/gate.md#baseline): the metrics of a new compare run against
// those of an earlier one (the last good run), metric by metric, with a tolerance and the sampled
// oracle's own uncertainty. The files are read by the command (cli/gate_command.cpp); this
// compares.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/compare/metric_table.h"

namespace so {

// The metrics the baseline can compare: those compared by default in the metric table's order,
// then the costs compared when named, in the order of the cost axes (frame time, the passes, the
// other times, memory, work); those whose BaselineRule is not Never (the others, such
// as counted_pixels, excluded_share, the predicted aliasing, the oracle's costs and the cost
// quartiles, are not quality metrics and are never compared). Their tolerances and oracle noise are
// the table's.
const std::vector<const MetricInfo*>& baselineMetricTable();

// V and share metrics take the limits file's baseline.default; the others keep their own.
bool takesFileDefault(const MetricInfo& m);

struct BaselineCheck {
    std::string scene, light, label, metric;
    std::optional<double> baseline, value;  // none: null (not applicable) in that run
    Better better = Better::Lower;
    Tolerance tolerance;
    double noise = 0.0;  // sqrt(h_old^2 + h_new^2) of the oracle's stated half-widths, or 0

    // How much worse (> 0) or better (< 0) the new value is, in the metric's unit: for
    // SmallerMagnitude, the change of |x|. Valid only when both values are present.
    double worsening() const;
    // abs + rel * |baseline score| + noise.
    double allowed() const;
    bool applicable() const { return baseline && value; }
    bool regressed() const { return applicable() && worsening() > allowed(); }
    bool improved() const { return applicable() && -worsening() > allowed(); }
};

// A row (scene file name, light, label) present in one run only.
struct BaselineRow {
    std::string scene, light, label;
};

struct BaselineComparison {
    std::vector<BaselineCheck> checks;  // every compared (scene, light, label, metric)
    std::vector<BaselineRow> missing;   // in the baseline, not in the new run: fails
    std::vector<BaselineRow> added;     // in the new run only: passes, with a note
    size_t regressions() const;
    bool failed() const { return regressions() > 0 || !missing.empty(); }
};

// What the limits file's `baseline` object (limits_format 2) says: per compared metric its
// tolerance, in the order of the table.
struct BaselineSettings {
    std::vector<std::pair<const MetricInfo*, Tolerance>> compared;
};

// Reads `limits`'s `baseline` object (null limits, or none there: the built-in defaults). Throws
// InputError naming the file and field: an unknown key or metric, a tolerance that is not a finite
// number >= 0.
BaselineSettings readBaselineSettings(const nlohmann::json* limits, const std::string& limitsPath);

// Compares the rows of `metrics` with those of `baseline`, matched by (scene file name, light,
// label; the n-th row of a label given twice matches the other run's n-th, labelled LABEL#n).
// `limits` (may be null: the built-in tolerances) is a limits file whose optional `baseline`
// object sets tolerances and which metrics are compared. Throws InputError naming the file and
// field on a malformed file or schema versions whose metrics differ in meaning.
BaselineComparison compareToBaseline(const nlohmann::json& metrics, const std::string& metricsPath,
                                     const nlohmann::json& baseline,
                                     const std::string& baselinePath, const nlohmann::json* limits,
                                     const std::string& limitsPath);

}  // namespace so
