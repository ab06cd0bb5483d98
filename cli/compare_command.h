// `shadow-oracle compare`: the oracle (reused from a cache keyed by scene content and oracle
// options) against each technique, metrics per scene x light x technique (docs/metrics.md), written
// as metrics.json, metrics.csv and an error EXR per technique (docs/cli.md). The comparison and its
// files are raster_compare/pipeline's (compare_scene.h, compare_output.h); this calls them and
// prints.
#pragma once

#include <string>

#include "raster_compare/pipeline/compare_scene.h"

namespace so {

// `--image LABEL=PATH`: split at the first '='; throws InputError naming --image on an empty label
// or path.
ImageSpec parseImageSpec(const std::string& text);

// The command's callbacks: warnings on stderr ("warning: ..."), the camera path's frames and the
// groups of techniques a line each as they are done.
CompareCallbacks printingCallbacks();

// metrics.json, the CSVs, the rows' folders and (options.writeReport) oracle.exr and report.html
// into run.out; a summary on stdout. Returns the exit code: 3 when --verify found disagreements.
// The report takes the rows' images (run.comparison's reports are moved from).
int writeCompareOutputs(const CompareOptions& options, CompareRun& run);
// `shadow-oracle compare`: both.
int runCompareCommand(const CompareOptions& options);

}  // namespace so
