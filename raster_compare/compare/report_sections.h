// Compare's report (report.h) in parts, shared by its files: the helpers both use, the tables and
// the chart of error against cost with its budget tables (report_tables.cpp); the images, the
// flicker strip, the sequence chart and the page around them are report.cpp. Every number the
// tables and the chart show is read from the techniques' typed rows (result_row.h).
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/report.h"

namespace so::report_parts {

std::string html(const std::string& s);
// `digits` significant digits; "–" for none.
std::string num(std::optional<double> v, int digits = 4);

// The techniques grouped by family, families in the order they first appear, techniques in the
// order given within each.
std::vector<const ReportTechnique*> byFamily(const ReportInput& in);
std::string lightId(const ReportInput& in, size_t li);
std::string rowId(size_t li, size_t k);
// The technique's row of light li (ReportInput::lights' order).
const LightRow& lightRow(const ReportTechnique& t, const ReportInput& in, size_t li);

// The value with its unit, where a column's header would say it: "12.3 ms", "195.48 MiB".
std::string withUnit(const MetricInfo& m, double v);
// An area light's page: its techniques have a penumbra error.
bool hasPenumbra(const ReportInput& in, size_t li);

// Per light: the summary table of the columns some technique has a value in.
void writeSummary(std::ostream& o, const ReportInput& in, size_t li);
// The data the script draws one light's chart from (report_assets.h).
nlohmann::json lightData(const ReportInput& in, size_t li);
// The chart's box: its selects, the chart the script draws, the budget tables of each cost. `d`:
// the light's lightData.
void writeChartBox(std::ostream& o, const ReportInput& in, size_t li, const nlohmann::json& d);
// Light li's contact=on settings against their contact=off ones (contact_pairs.h).
void writeContactPairs(std::ostream& o, const ReportInput& in, size_t li);
// Every column, every technique and light: the "All metrics" table.
void writeAllMetrics(std::ostream& o, const ReportInput& in);

}  // namespace so::report_parts
