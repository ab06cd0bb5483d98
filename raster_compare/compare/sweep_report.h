// The HTML report of a sweep (docs/sweep.md, "The report"): per scene and light, the Pareto front
// of each artifact's error against frame time and against memory over every setting swept, the
// cheapest setting per technique at a few error budgets, contact=on against contact=off where
// both ran (contact_pairs.h), heat maps over the two-parameter grids
// (e.g. slope-bias alpha x min coloured by acne and by peter-panning), and the failed tasks with
// their logs. Self-contained: style and script inline, no images, no network.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "raster_compare/compare/result_row.h"

namespace so {

// One finished task for one light: a row of the merged metrics_wide.csv.
struct SweepRow {
    std::string task;   // the task's stable id
    std::string scene;  // the scene as the spec names it (path)
    // The task's row of compare's metrics.json, read back (result_row.h): its label
    // ("slope-bias:alpha=2,min=0.5"), technique and typed parameters (defaults included: what the
    // contact pairs compare, contact_pairs.h), and in `lights` this row's one light.
    ResultRow result;
    // The parameters the spec swept for this technique (more than one value), in the spec's order,
    // with this task's values typed as `result.parameters` are ("denoiser=svgf" a name).
    std::vector<std::pair<std::string, ParamValue>> swept;
    const LightRow& light() const { return result.lights.front(); }
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
