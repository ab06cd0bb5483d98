// `shadow-oracle metrics`: every public metric with its unit, which way is better, where it
// applies and its meaning, from the metric table (raster_compare/compare/metric_table.h), as text
// or as the Markdown table of docs/metrics.md (scripts/update-docs writes it there; a test fails
// when the document differs).
#pragma once

#include <string>

namespace so {

std::string metricsListing(bool markdown);

int runMetricsCommand(bool markdown);

}  // namespace so
