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

// The command's callbacks: warnings on stderr ("warning: ..."), the camera path's and the
// sequence's frames and the groups of techniques a line each as they are done; without
// `progress` (--quiet) the warnings alone.
CompareCallbacks printingCallbacks(bool progress = true);

// What was compared and the files written (writeCompareRun), on stdout; the oracle's --verify
// count. Returns the exit code: 3 when --verify found disagreements.
int printCompareSummary(const CompareOptions& options, const CompareRun& run,
                        const CompareOutputFiles& files);
// `shadow-oracle compare`: compareScene, writeCompareRun and the summary.
int runCompareCommand(CompareOptions options, bool progress = true);

}  // namespace so
