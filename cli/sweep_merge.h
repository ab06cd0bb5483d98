// `shadow-oracle sweep-merge DIR`: the rows of a sweep's finished tasks into one metrics.csv,
// metrics_wide.csv and metrics.json, and the sweep report (report.html), by the library's
// mergeSweep (raster_compare/pipeline/sweep_merge.h); the tasks that did not finish are listed
// with their logs (docs/sweep.md).
#pragma once

#include <string>

namespace so {

struct SweepMergeOptions {
    std::string dir;
    bool quiet = false;  // no list of the unfinished tasks on stderr
    // The local sweep that merges has just checked every image row against its image
    // (dropStaleImageRows) and written the others from the images as read: the merge need not
    // read every image again. A standalone sweep-merge (a Slurm merge job) checks them.
    bool imagesChecked = false;
};

// 0 when every task of the plan finished, 1 when some did not (the files are written either way,
// over the finished ones).
int runSweepMerge(const SweepMergeOptions& options);

}  // namespace so
