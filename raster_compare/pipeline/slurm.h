// A sweep on a Slurm cluster (docs/sweep.md, "On a Slurm cluster"): batch scripts for a job array
// of the oracles (one task per scene), a job array of the technique tasks that waits for them
// (afterok) and a merge job that waits for the array (afterany, so it reports failed tasks),
// written into DIR/slurm and submitted with sbatch. Only the tasks without a row are submitted, so
// submitting again after failures resubmits just those. No terminal: what was written and
// submitted is returned; `shadow-oracle sweep --slurm` prints it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "raster_compare/pipeline/sweep_runner.h"
#include "raster_compare/pipeline/sweep_spec.h"

namespace so {

struct SlurmOptions {
    std::string partition;                // --partition; empty: the cluster's default
    int maxConcurrent = 0;                // --max-concurrent K: "%K" on the arrays; 0: no limit
    std::vector<std::string> sbatchArgs;  // --sbatch-arg, each an #SBATCH line of every script
    bool dryRun = false;                  // write the scripts, submit nothing
    // What the array tasks run: the local runner's command (sweep_runner.h), given the array
    // index as the shell word "$SLURM_ARRAY_TASK_ID".
    SweepTaskCommand taskCommand;
    std::vector<std::string> mergeCommand;  // what the merge job runs
    // What the caller calls where the options come from, the sweep's folder and the cluster
    // option, as the errors name them ("command line", "--out", "--slurm"); no defaults.
    std::string source, outName, slurmName;
};

struct SlurmScript {
    std::string name;  // file name in DIR/slurm
    std::string text;
};

struct SlurmSubmission {
    bool nothingToSubmit = false;      // every task has its row
    size_t tasks = 0, scenes = 0;      // submitted (or, in a dry run, to be)
    std::vector<SlurmScript> scripts;  // oracles, tasks, merge; written into DIR/slurm
    // The jobs' ids; empty in a dry run.
    std::string oraclesJob, tasksJob, mergeJob;
};

// "0-3,7,9-10": sorted indices as a Slurm array range list.
std::string slurmArrayList(const std::vector<size_t>& indices);

// Writes the scripts and submits them (not with dryRun). InputError (naming outName or slurmName)
// when the folder's path or the cluster cannot take the sweep; std::runtime_error when sbatch
// fails.
SlurmSubmission submitSweepToSlurm(const SweepPlan& plan, const std::filesystem::path& dir,
                                   const SlurmOptions& options);

}  // namespace so
