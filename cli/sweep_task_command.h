// `shadow-oracle sweep-task DIR --index K` and `--oracle S`: one task of a sweep planned in
// DIR/sweep.json (docs/sweep.md), run by raster_compare/pipeline/sweep_task.h. What a local
// `sweep --jobs N` runs as child processes and what each Slurm array task runs.
#pragma once

#include <string>

namespace so {

struct SweepTaskOptions {
    std::string dir;
    long index = -1;   // --index K: technique task K of the plan
    long oracle = -1;  // --oracle S: the oracle of scene S (traced once, shared by its tasks)
};

// 0 when the row (or the oracle) is in place, whether made now or before; InputError on a bad
// folder or index; any other failure propagates (the task's log says why).
int runSweepTask(const SweepTaskOptions& options);

}  // namespace so
