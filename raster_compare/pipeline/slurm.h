// A sweep on a Slurm cluster (docs/sweep.md, "On a Slurm cluster"): batch scripts for a job array
// of the oracles (one task per scene), a job array of the technique tasks that waits for them
// (afterok) and a merge job that waits for the array (afterany, so it reports failed tasks),
// written into DIR/slurm and submitted with sbatch. Only the tasks without a row are submitted, so
// submitting again after failures resubmits just those.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "raster_compare/pipeline/sweep_spec.h"

namespace so {

struct SlurmOptions {
    std::string partition;                // --partition; empty: the cluster's default
    int maxConcurrent = 0;                // --max-concurrent K: "%K" on the arrays; 0: no limit
    std::vector<std::string> sbatchArgs;  // --sbatch-arg, each an #SBATCH line of every script
    bool dryRun = false;                  // print the scripts and the sbatch commands only
};

// "0-3,7,9-10": sorted indices as a Slurm array range list.
std::string slurmArrayList(const std::vector<size_t>& indices);

// Writes the scripts and submits them (or prints them with dryRun); returns the exit code.
int submitSweepToSlurm(const SweepPlan& plan, const std::filesystem::path& dir,
                       const SlurmOptions& options);

}  // namespace so
