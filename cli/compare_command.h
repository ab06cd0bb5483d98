// `shadow-oracle compare`: the oracle (reused from a cache keyed by scene content and oracle
// options) against each technique, metrics per scene x light x technique (docs/metrics.md), written
// as metrics.json, metrics.csv and an error EXR per technique (docs/cli.md). The comparison itself
// is raster_compare/comparison's; this parses, calls and writes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/visibility_image.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/comparison/comparison.h"
#include "raster_compare/gl/renderer.h"

namespace so {

// `--image LABEL=PATH`: split at the first '='; throws InputError naming --image on an empty label
// or path.
ImageSpec parseImageSpec(const std::string& text);

struct CompareOptions {
    std::string scenePath;
    std::string outDir;
    std::vector<std::string> techniques;
    // --image LABEL=PATH (parseImageSpec), or a sweep's image tasks (makeImageSpec: their labels
    // hold '=').
    std::vector<ImageSpec> images;
    ImageEncoding imageEncoding = ImageEncoding::Linear;
    // --points GBUFFER.exr: the oracle at a renderer's own G-buffer points (trace --points) instead
    // of the scene camera's pixels; images only, the G-buffer's size.
    std::string pointsPath;
    OracleOptions oracle;
    RasterOptions raster;
    std::filesystem::path cacheDir;  // empty: defaultOracleCacheDir()
    bool useCache = true;
    bool embedImages = false;  // report.html's images inside it, not in report_images/
    int boundaryRadius = 2;
    double contactThresholdRelative = 0.01;  // of the scene's bounding-box diagonal
    // --frames-path N (>= 2): the scene's camera path in N frames, for temporal_flicker_rate;
    // 0: none.
    int pathFrames = 0;
    // report.html and the copy of the oracle it shows; a sweep's task writes neither (its report
    // is sweep-merge's, docs/sweep.md).
    bool writeReport = true;
    // Per technique raster.exr and the error EXR; a sweep's task only when it keeps its outputs.
    bool writeImages = true;
};

// `metrics`, when given, gets what metrics.json holds (a sweep task's row is made from it).
int runCompareCommand(const CompareOptions& options, nlohmann::json* metrics = nullptr);

}  // namespace so
