// The HTML report of a sweep (docs/sweep.md, "The report"): per scene and light, the Pareto front
// of each artifact's error against frame time and against memory over every setting swept, the
// cheapest setting per technique at a few error budgets, contact=on against contact=off where
// both ran (contact_pairs.h), heat maps over the two-parameter grids
// (e.g. slope-bias alpha x min coloured by acne and by peter-panning), and the failed tasks with
// their logs. Self-contained: style and script inline, no images, no network.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace so {

// One finished task for one light: a row of the merged metrics_wide.csv.
struct SweepRow {
    std::string task;   // the task's stable id
    std::string scene;  // the scene as the spec names it (path)
    std::string light;
    std::string technique;  // its name: "slope-bias"
    std::string label;      // the setting as compare takes it: "slope-bias:alpha=2,min=0.5"
    // The parameters the spec swept for this technique (more than one value), in the spec's order,
    // with this task's values.
    std::vector<std::pair<std::string, double>> swept;
    // Every numeric metric of the light's row in compare's metrics.json, flattened with dots
    // (docs/metrics.md): "acne_rate", "peter_panning_rate", "mae", "cost.frame_ms",
    // "cost.memory_bytes", ... A metric that is null (not applicable) is absent.
    std::map<std::string, double> metrics;
    // Every parameter of the setting, defaults included, as numbers (compare's metrics.json
    // `parameters`): what the contact pairs compare (contact_pairs.h).
    std::map<std::string, double> parameters;
};

struct SweepFailure {
    std::string task;
    std::string scene;
    std::string label;
    std::string reason;  // "exit 2: <last line of the log>", "not run", ...
    std::string log;     // its log file, relative to the report
};

struct SweepReportInput {
    std::string specFile;
    std::string sweepName;
    std::vector<SweepRow> rows;
    std::vector<SweepFailure> failed;
    size_t tasks = 0;  // in the plan, finished or not
    // Error budgets (of each artifact's metric) for the best-setting tables.
    std::vector<double> errorBudgets = {0.0, 0.001, 0.01};
    std::string timedOn;  // the GL renderers that measured the times, as rows reported them
    std::vector<std::pair<std::string, std::string>> provenance;
};

void writeSweepReport(const std::string& path, const SweepReportInput& in);

}  // namespace so
