// `shadow-oracle compare`: the oracle (reused from a cache keyed by scene content and oracle
// options) against each technique, metrics per scene x light x technique (docs/metrics.md), written
// as metrics.json, metrics.csv and an error EXR per technique (docs/cli.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/visibility_image.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/gl/renderer.h"

namespace so {

struct TechniqueSpec {
    std::string name;
    std::vector<std::string> settings;  // key=value
    std::string label;                  // "name" or "name:k=v,k=v", as given
    std::string fileLabel;              // the label made safe for file names
};
// "name[:key=value,...]"; throws InputError on an empty name.
TechniqueSpec parseTechniqueSpec(const std::string& spec);

// `--image LABEL=PATH`: a renderer's image judged like a technique (docs/external.md).
struct ImageSpec {
    std::string label;      // as given; the row's label
    std::string fileLabel;  // made safe for file names, as TechniqueSpec's
    std::string path;
};
// Splits at the first '='; throws InputError naming --image on an empty label or path.
ImageSpec parseImageSpec(const std::string& text);
// A label and a path as they are (a sweep's image tasks, whose labels hold '=').
ImageSpec makeImageSpec(const std::string& label, const std::string& path);

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
