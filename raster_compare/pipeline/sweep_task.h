// One task of a sweep planned in DIR/sweep.json (docs/sweep.md): a technique or image task
// (compareScene of one setting, written as its row) or the oracle of a scene (traced once, shared
// by its tasks). What `shadow-oracle sweep-task` runs, as a local `sweep --jobs N`'s child process
// and as each Slurm array task: the same code either way. No terminal: what happened is returned,
// warnings and progress go to the callbacks.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

#include "raster_compare/pipeline/compare_scene.h"
#include "raster_compare/pipeline/sweep_spec.h"

namespace so {

struct SweepTaskCallbacks {
    // The task's comparison's (and the oracle task's scene and cache's warnings).
    CompareCallbacks compare;
    // When the spec keeps outputs: the task's compare folder was written (before it is moved to
    // DIR/outputs).
    std::function<void(const CompareOptions&, const CompareRun&, const CompareOutputFiles&)>
        outputsWritten;
};

struct SweepOracleTaskResult {
    std::string scene;  // its name in the plan
    bool fromCache = false;
    std::string key;  // the oracle cache's
};

struct SweepTechniqueTaskResult {
    std::string id, label, scene;
    std::filesystem::path row;
    bool alreadyFinished = false;  // its row was there: nothing was done
    double seconds = 0;
    // 3 when the spec keeps outputs and the oracle's --verify found disagreements (compare's
    // code; the row is then not written), else 0.
    int exitCode = 0;
};

// The oracle of scene `scene` (< plan.scenes.size()) into DIR/oracles (oracle_cache.h:
// content-addressed, so a present and valid entry is loaded, never traced again).
SweepOracleTaskResult runSweepOracleTask(const std::filesystem::path& dir, const SweepPlan& plan,
                                         size_t scene, const SweepTaskCallbacks& callbacks = {});

// Task `index` (< plan.taskCount): its row written last, atomically (it marks the task done);
// nothing when the row is there already. InputError on a bad folder; any other failure propagates
// (the task's log says why).
SweepTechniqueTaskResult runSweepTechniqueTask(const std::filesystem::path& dir,
                                               const SweepPlan& plan, size_t index,
                                               const SweepTaskCallbacks& callbacks = {});

}  // namespace so
