// The compare command's output folder (docs/cli.md, docs/metrics.md): metrics.json, metrics.csv,
// metrics_wide.csv, a folder per row (raster.json, raster.exr) with its error EXR beside it, and
// report.html with the oracle.exr it shows. The command, a sweep's task, the C++ API
// (writeCompareOutput) and Python write the same files through here, so `gate`, `index` and
// `sweep-merge` read them alike.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/compare_option_table.h"
#include "core/image.h"
#include "core/scene.h"
#include "oracle/area_shadow.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/compare/report.h"
#include "raster_compare/pipeline/comparison.h"

namespace so {

struct CompareOutputOptions {
    std::string scenePath;  // metrics.json's scene.file: the path as the caller gave it
    int boundaryRadius =
        kDefaultBoundaryRadius;  // as the comparison was made with (metrics.json "options")
    AreaSampling sampling;       // the oracle's, as the report's provenance states it
    // report.html (images in report_images/, or inside it with embedImages) and the oracle.exr it
    // shows; a sweep's task writes neither.
    bool writeReport = true, embedImages = false;
    // Each row's raster.exr and error_LABEL.exr; raster.json is always written.
    bool writeImages = true;
};

struct CompareOutputFiles {
    std::filesystem::path metricsJson, metricsCsv, metricsWideCsv;
    std::optional<std::filesystem::path> report;
};

// The error EXR of one row: per light, one channel per artifact class (NAME.<layer>) and the
// error (NAME.error), as docs/exr-channels.md names them.
ChannelImage errorImage(const ReportTechnique& row);

// Writes the folder `dir` (created if missing; an InputError naming it when it cannot be). The
// report takes the rows' images: `comparison`'s rows' reports are moved from when writeReport.
CompareOutputFiles writeCompareOutput(const std::filesystem::path& dir, const Scene& scene,
                                      const CachedOracle& oracle, Comparison& comparison,
                                      const CompareOutputOptions& options);

}  // namespace so
