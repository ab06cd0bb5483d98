// `shadow-oracle compare`: the oracle (reused from a cache keyed by scene content and oracle
// options) against each technique, metrics per scene x light x technique (docs/metrics.md), written
// as metrics.json, metrics.csv and an error EXR per technique (docs/cli.md). The comparison itself
// is raster_compare/comparison's; this parses, calls and writes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/visibility_image.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/gl/renderer.h"
#include "raster_compare/pipeline/comparison.h"

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

// What a comparison of one scene produced, typed: the command writes it, a sweep task makes its
// row from it.
struct CompareRun {
    Scene scene;
    OracleOptions oracleOptions;  // the options', at the comparison's image size
    CachedOracle oracle;
    bool atPoints = false;  // the oracle at --points' G-buffer
    Comparison comparison;
    std::filesystem::path out;  // the output folder, made; empty when options.outDir is
};

// Checks the options (InputError naming their flags, before any work), loads the scene, makes the
// output folder (unless options.outDir is empty), traces or reads the oracle and compares. Writes
// no files but the folder; prints the warnings.
CompareRun compareScene(const CompareOptions& options);
// metrics.json, the CSVs, the rows' folders and (options.writeReport) oracle.exr and report.html
// into run.out; a summary on stdout. Returns the exit code: 3 when --verify found disagreements.
// The report takes the rows' images (run.comparison's reports are moved from).
int writeCompareOutputs(const CompareOptions& options, CompareRun& run);
// `shadow-oracle compare`: both.
int runCompareCommand(const CompareOptions& options);

}  // namespace so
