// The merge of a sweep (docs/sweep.md): the rows of its finished tasks into one metrics.csv,
// metrics_wide.csv and metrics.json, and the sweep report (report.html). What `sweep-merge` and a
// local `sweep` call; the tasks that did not finish come back with why, for the caller to list.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "raster_compare/compare/sweep_report.h"

namespace so {

struct SweepMerge {
    std::string name;  // the sweep's
    size_t tasks = 0, finished = 0;
    std::vector<SweepFailure> failed;   // the tasks without a fresh row, with why and their log
    std::vector<std::string> warnings;  // rows that did not parse (counted as not finished)
    std::filesystem::path metricsCsv, metricsWideCsv, metricsJson, report;
};

// Writes the four files over the finished tasks (whether or not every task finished). With
// imagesChecked, the image rows are taken as fresh: the local sweep that merges has just checked
// every one against its image (dropStaleImageRows); a standalone merge reads the images again.
// InputError on a bad folder or a malformed row.
SweepMerge mergeSweep(const std::filesystem::path& dir, bool imagesChecked);

}  // namespace so
