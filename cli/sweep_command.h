// `shadow-oracle sweep SPEC.json --out DIR [--jobs N | --slurm ...]`: plans the sweep
// (sweep_spec.h) into DIR/sweep.json and runs its unfinished tasks, locally as N child processes
// with progress and ETA, or as Slurm job arrays (slurm.h); locally it then merges
// (sweep_merge.h). Rerunning resumes: finished tasks are skipped, failed ones retried.
#pragma once

#include <string>

#include "raster_compare/pipeline/slurm.h"

namespace so {

struct SweepOptions {
    std::string specPath;
    std::string outDir;
    int jobs = 1;
    bool slurm = false;
    SlurmOptions slurmOptions;
    bool progress = true;
};

// 0 when every task finished (or was submitted), 1 when some failed, 2 on bad input.
int runSweepCommand(const SweepOptions& options);

}  // namespace so
