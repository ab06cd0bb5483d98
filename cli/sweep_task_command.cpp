#include "cli/sweep_task_command.h"

#include <iostream>

#include "cli/compare_command.h"
#include "core/error.h"
#include "raster_compare/pipeline/sweep_task.h"

namespace so {

namespace {

SweepTaskCallbacks printingTaskCallbacks() {
    SweepTaskCallbacks callbacks;
    callbacks.compare = printingCallbacks();
    callbacks.outputsWritten = [](const CompareOptions& c, const CompareRun& run,
                                  const CompareOutputFiles& files) {
        printCompareSummary(c, run, files);
    };
    return callbacks;
}

int runOracleTask(const std::string& dir, const SweepPlan& plan, size_t scene) {
    const SweepOracleTaskResult r = runSweepOracleTask(dir, plan, scene, printingTaskCallbacks());
    std::cout << "oracle of " << r.scene << ": " << (r.fromCache ? "present" : "traced") << " ("
              << r.key << ")\n";
    return 0;
}

int runTechniqueTask(const std::string& dir, const SweepPlan& plan, size_t index) {
    const SweepTechniqueTaskResult r =
        runSweepTechniqueTask(dir, plan, index, printingTaskCallbacks());
    if (r.alreadyFinished)
        std::cout << "task " << index << " (" << r.id << ") already finished: " << r.row.string()
                  << "\n";
    else if (r.exitCode == 0)
        std::cout << "task " << index << " (" << r.id << ", " << r.label << " on " << r.scene
                  << ") finished in " << r.seconds << " s\n";
    return r.exitCode;
}

}  // namespace

int runSweepTask(const SweepTaskOptions& options) {
    const SweepPlan plan = readPlan(options.dir, /*withTasks=*/false);
    if ((options.index >= 0) == (options.oracle >= 0))
        throwInputError("command line", "--index", "give exactly one of --index K and --oracle S");
    if (options.oracle >= 0) {
        if (size_t(options.oracle) >= plan.scenes.size())
            throwInputError("command line", "--oracle",
                            std::to_string(options.oracle) + " is out of range: the sweep has " +
                                std::to_string(plan.scenes.size()) + " scenes");
        return runOracleTask(options.dir, plan, size_t(options.oracle));
    }
    if (size_t(options.index) >= plan.taskCount)
        throwInputError("command line", "--index",
                        std::to_string(options.index) + " is out of range: the sweep has " +
                            std::to_string(plan.taskCount) + " tasks");
    return runTechniqueTask(options.dir, plan, size_t(options.index));
}

}  // namespace so
