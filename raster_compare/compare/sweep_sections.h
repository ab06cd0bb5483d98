// The sweep report's parts (sweep_report.h), shared by its files: the rows grouped by scene and
// light, the helpers every section reads them with, and the sections themselves: the Pareto
// fronts and budget tables (sweep_fronts.cpp), the heat maps and verdicts over the swept
// parameters (sweep_grids.cpp); the page around them is sweep_report.cpp.
#pragma once

#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/sweep_report.h"

namespace so::sweep {

std::string html(const std::string& s);
// Four significant digits: enough to tell settings apart, short enough for a cell.
std::string num(double v);
// Full precision, for the data- attributes that tests and tools read instead of the text.
std::string exact(double v);

extern const std::string kMae, kAcne, kPeterPanning;

// The row's value of a metric of the table (none: null or absent).
std::optional<double> metricOf(const SweepRow& r, const std::string& metric);
// The metric's name for people, the metric table's label ("acne", "penumbra mae").
std::string metricName(const std::string& metric);
// "<b>acne</b> <code>acne_rate</code>": the name, and the key to look it up by in docs/metrics.md.
std::string metricTitle(const std::string& metric);

// A cost axis: its metric, and from the metric table its name, the unit it is shown in and the
// factor to that unit.
struct Cost {
    std::string key, name, unit;
    double scale;
};
// The metric table's cost axes but the single passes' times: frame time and memory, then the
// work of a frame (docs/metrics.md, Work).
const std::vector<Cost>& costs();

// One section of the page: the rows of one light of one scene.
struct Group {
    std::string scene, light;
    std::vector<const SweepRow*> rows;
};

std::vector<std::string> techniquesOf(const std::vector<const SweepRow*>& rows);
std::vector<const SweepRow*> rowsOf(const Group& g, const std::string& technique);
bool anyHas(const std::vector<const SweepRow*>& rows, const std::string& metric);
bool anyNonZero(const std::vector<const SweepRow*>& rows, const std::string& metric);
// mae, then the artifacts in artifacts.h's order: those some row measured (null is "does not
// apply", e.g. penumbra_mae of a hard light).
std::vector<std::string> errorMetrics(const std::vector<const SweepRow*>& rows);
// The setting without the technique's name, which its row or section already shows.
std::string shortLabel(const SweepRow& r);
// The swept values as the label writes them, "alpha=2, min=0.5": what a person changes in the
// spec.
std::string sweptName(const SweepRow& r);

// Technique name -> its colour, the same in every section.
using ColourMap = std::map<std::string, std::string>;

void writeFronts(std::ostream& o, const Group& g, const SweepReportInput& in,
                 const ColourMap& colours);
void writeBudgets(std::ostream& o, const Group& g, const std::vector<double>& budgets);
void writeVerdicts(std::ostream& o, const Group& g);
void writeHeatMaps(std::ostream& o, const Group& g);

}  // namespace so::sweep
