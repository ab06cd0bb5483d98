#include "cli/sweep_command.h"

#include <iostream>
#include <set>

#include "cli/output.h"
#include "cli/progress_bar.h"
#include "cli/sweep_merge.h"
#include "core/error.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/pipeline/sweep_runner.h"

namespace so {

namespace fs = std::filesystem;

namespace {

// DIR/sweep.json: written on the first run; a later run must be of the same spec.
void keepPlan(const fs::path& dir, const SweepPlan& plan) {
    if (fs::exists(dir / "sweep.json")) {
        const SweepPlan old = readPlan(dir, /*withTasks=*/false);
        if (old.specHash != plan.specHash)
            throwInputError(plan.specFile.string(), "",
                            "differs from the spec of the sweep in " + dir.string() + " (" +
                                old.specFile.string() +
                                "): give another --out, or remove that folder");
    }
    writePlan(dir, plan);
}

void printNotice(const std::string& line) {
    std::cerr << line << "\n";
}

// The tasks as child processes of this program (`sweep-task`), the pool's state on the bar; then
// the merge.
// One task as a child process: this program's `sweep-task`, run by the local pool and by the
// Slurm scripts alike.
SweepTaskCommand taskCommand(const std::string& exe, const fs::path& dir) {
    return [exe, dir](bool oracle, const std::string& number) {
        return std::vector<std::string>{exe, "sweep-task", dir.string(),
                                        oracle ? "--oracle" : "--index", number};
    };
}

int runLocally(const SweepPlan& plan, const fs::path& dir, const SweepOptions& o) {
    const std::string exe = thisExecutable().string();
    ProgressBar bar(o.progress);
    SweepRunCallbacks callbacks;
    callbacks.notice = printNotice;
    callbacks.progress = [&](const std::string& stage, size_t ended, size_t total,
                             const std::string& note) {
        bar.setNote(note);
        bar.update(stage, ended, total);
    };
    runSweepLocally(plan, dir, o.jobs, taskCommand(exe, dir), callbacks);
    return runSweepMerge({dir.string(), false, true});
}

// What --slurm wrote and submitted (with --dry-run: the scripts and the sbatch commands).
int submitToSlurm(const SweepPlan& plan, const fs::path& dir, const SweepOptions& options) {
    SlurmOptions o = options.slurmOptions;
    o.taskCommand = taskCommand(thisExecutable().string(), dir);
    o.mergeCommand = {thisExecutable().string(), "sweep-merge", dir.string()};
    o.source = "command line";
    o.outName = "--out";
    o.slurmName = "--slurm";
    const SlurmSubmission r = submitSweepToSlurm(plan, dir, o);
    if (r.nothingToSubmit) {
        std::cout << "all " << plan.tasks.size() << " tasks of " << dir.string()
                  << " are finished: nothing to submit (shadow-oracle sweep-merge " << dir.string()
                  << " merges them)\n";
        return 0;
    }
    if (o.dryRun) {
        const char* deps[3] = {"", " --dependency=afterok:<oracles job>",
                               " --dependency=afterany:<tasks job>"};
        for (int k = 0; k < 3; ++k)
            std::cout << "# sbatch --parsable" << deps[k] << " "
                      << (dir / "slurm" / r.scripts[k].name).string() << "\n"
                      << r.scripts[k].text << "\n";
        std::cout << "# dry run: " << r.tasks << " tasks over " << r.scenes
                  << " scenes, nothing submitted\n";
        return 0;
    }
    const std::string limit = o.maxConcurrent > 0 ? std::to_string(o.maxConcurrent) : "";
    std::cout << "submitted to Slurm: oracles job " << r.oraclesJob << " (" << r.scenes
              << " scenes), tasks job " << r.tasksJob << " (" << r.tasks << " of "
              << plan.tasks.size() << " tasks" << (limit.empty() ? "" : ", " + limit + " at once")
              << "), merge job " << r.mergeJob << "\n  logs: " << (dir / "logs").string()
              << "\n  when job " << r.mergeJob << " ends: " << (dir / "report.html").string()
              << "\n";
    return 0;
}

}  // namespace

int runSweepCommand(const SweepOptions& options) {
    if (options.jobs < 1) throwInputError("command line", "--jobs", "must be at least 1");
    std::set<std::string> said;  // a former parameter name's notice, once per sweep
    const SweepPlan plan = planSweep(
        options.specPath, [&said](const std::string& name, const std::vector<std::string>& s) {
            const std::unique_ptr<Technique> t = createTechnique(name, s);
            for (const std::string& notice : t->values().deprecations())
                if (said.insert(notice).second) printWarnings({notice});
            return t->values().all();
        });
    const fs::path dir = fs::absolute(makeOutputDir(options.outDir, "--out"));
    keepPlan(dir, plan);
    SweepRunCallbacks notices;
    notices.notice = printNotice;
    dropStaleRows(plan, dir, notices);
    if (options.slurm) return submitToSlurm(plan, dir, options);
    return runLocally(plan, dir, options);
}

}  // namespace so
