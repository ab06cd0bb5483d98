// One scene compared as `shadow-oracle compare` and a sweep's task do it: the options checked
// before any work, the scene loaded, the renderers' images read, the oracle traced or read from
// its cache (keyed by scene content and oracle options) or traced at a G-buffer's points, and
// compareWithOracle. No terminal: warnings and progress go to the caller's callbacks, and the
// errors name the caller's options by the names it gives (CompareOptionNames).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/compare_option_table.h"
#include "core/progress.h"
#include "core/visibility_image.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/pipeline/compare_output.h"
#include "raster_compare/pipeline/comparison.h"

namespace so {

// What the caller calls the options the checks refuse: their errors read "SOURCE: NAME: ...". No
// defaults: the command passes its flags ("command line", "--technique"), a sweep's task its
// spec's keys (sweep_task.h), so that an error names what the user wrote.
struct CompareOptionNames {
    std::string source;      // where the options come from: "command line", the spec's path
    std::string technique;   // "--technique"
    std::string image;       // "--image"
    std::string points;      // "--points"
    std::string framesPath;  // "--frames-path"
    std::string verify;      // "--verify"
    std::string size;        // "--width and --height"
    std::string out;         // "--out"
    std::string sequence;    // "--sequence"
    std::string converge;    // "--converge"
};

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
    int boundaryRadius = kDefaultBoundaryRadius;
    double contactThresholdRelative = 0.01;  // of the scene's bounding-box diagonal
    // --frames-path N (>= 2): the scene's camera path in N frames, for temporal_flicker_rate;
    // 0: none.
    int pathFrames = 0;
    // --sequence: the scene's sequence judged frame by frame (sequence_compare.h); the comparison's
    // other metrics describe its last frame, the scene posed there. Not with pathFrames.
    bool sequence = false;
    // --converge N (1 to kMaxConvergeFrames): N still frames of the scene, the frame index turning,
    // the last one judged (ComparisonOptions::convergeFrames); 0: a single frame. Not with
    // pathFrames or sequence.
    int convergeFrames = 0;
    // report.html and the copy of the oracle it shows; a sweep's task writes neither (its report
    // is sweep-merge's, docs/sweep.md).
    bool writeReport = true;
    // Per technique raster.exr and the error EXR; a sweep's task only when it keeps its outputs.
    bool writeImages = true;
    CompareOptionNames names;
};

// Where a comparison reports as it goes; any may be empty.
struct CompareCallbacks {
    // Each warning as it is found: the scene loader's ("<scene file>: <text>"), the oracle
    // cache's and the comparison's (the GL driver's).
    std::function<void(const std::string&)> warning;
    // The camera path's frames and the techniques (ComparisonOptions::progress); can cancel.
    ProgressCallback progress;
    // Before each group of techniques is rendered together: their labels.
    std::function<void(const std::vector<std::string>&)> renderingGroup;
};

// What a comparison of one scene produced, typed: the command writes it, a sweep task makes its
// row from it.
struct CompareRun {
    Scene scene;                  // as loaded (with its motion, in a sequence)
    OracleOptions oracleOptions;  // the options', at the comparison's image size
    CachedOracle oracle;          // in a sequence, its last frame's
    bool atPoints = false;        // the oracle at --points' G-buffer
    Comparison comparison;
    std::filesystem::path out;  // the output folder, made; empty when options.outDir is
};

// The compare option table's values (core/compare_option_table.h): checks each of `values`
// (naming its field as `naming` says) and writes it into `o`.
void applyCompareOptions(const OptionValues& values, const OptionNaming& naming, CompareOptions& o);
// The keys applyCompareOptions can write, sorted (a test compares them with the table's).
std::vector<std::string> appliedCompareOptionKeys();

// Checks the options (InputError naming them as options.names does, before any work), loads the
// scene, makes the output folder (unless options.outDir is empty), traces or reads the oracle and
// compares. Writes no files but the folder.
CompareRun compareScene(const CompareOptions& options, const CompareCallbacks& callbacks = {});

// compare's output folder for a run (writeCompareOutput, with the options' choices of files).
CompareOutputFiles writeCompareRun(const CompareOptions& options, CompareRun& run);

}  // namespace so
