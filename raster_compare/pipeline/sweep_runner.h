// A sweep's folder across runs and its tasks run on this machine (docs/sweep.md): rows made stale
// by an edited scene or a re-rendered image removed, what killed tasks left cleaned up, and the
// unfinished tasks run as child processes, at most N at once, the oracles first. What
// `shadow-oracle sweep` does before it merges; the child's command line is the caller's
// (`shadow-oracle sweep-task ...`). No terminal: notices and the pool's progress go to the
// callbacks.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "raster_compare/pipeline/sweep_spec.h"

namespace so {

struct SweepRunCallbacks {
    // A line for the user: rows found stale and removed, what a run will do.
    std::function<void(const std::string&)> notice;
    // The pool's state as tasks start and end: its stage ("oracles", "tasks"), the tasks ended of
    // `total`, and a note ("3/12, 1 failed, 2 running").
    std::function<void(const std::string& stage, size_t ended, size_t total,
                       const std::string& note)>
        progress;
};

// The argv of the child process that runs one task: the oracle of scene S (oracle = true) or
// technique task K (runSweepOracleTask, runSweepTechniqueTask in a process of its own). `number`
// is S or K as text, or a shell word that expands to it (the Slurm scripts' array index): the
// local runner and the Slurm scripts (slurm.h) run the same command.
using SweepTaskCommand =
    std::function<std::vector<std::string>(bool oracle, const std::string& number)>;

// A scene edited since its rows were made (same name, other content) makes them stale: they are
// removed, so that its tasks run again, and the scene's hash is recorded for sweep-merge, which
// counts a row of another hash as not finished. A scene that does not load keeps its rows (its
// oracle task will fail and say why). Rows of images re-rendered since are removed too.
void dropStaleRows(const SweepPlan& plan, const std::filesystem::path& dir,
                   const SweepRunCallbacks& callbacks = {});

// Runs the plan's unfinished tasks, `jobs` (>= 1) at once: each scene's oracle, then the tasks of
// the scenes whose oracle succeeded. A failed task leaves its log (and no row); the caller merges.
void runSweepLocally(const SweepPlan& plan, const std::filesystem::path& dir, int jobs,
                     const SweepTaskCommand& command, const SweepRunCallbacks& callbacks = {});

}  // namespace so
