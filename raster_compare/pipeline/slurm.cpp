#include "raster_compare/pipeline/slurm.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <fstream>

#include "core/error.h"
#include "core/json_file.h"

namespace so {

namespace fs = std::filesystem;

namespace {

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// Runs a shell command, returning its exit status and standard output (stderr passes through).
int runCaptured(const std::string& command, std::string& output) {
    output.clear();
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return -1;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
    const int status = ::pclose(pipe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool onPath(const std::string& command) {
    std::string out;
    return runCaptured("command -v " + command + " >/dev/null 2>&1", out) == 0;
}

// The cluster's MaxArraySize (array indices must stay below it); 1001, Slurm's default, when
// scontrol cannot tell.
size_t maxArraySize() {
    std::string out;
    if (runCaptured("scontrol show config 2>/dev/null", out) != 0) return 1001;
    const size_t at = out.find("MaxArraySize");
    if (at == std::string::npos) return 1001;
    const size_t eq = out.find('=', at);
    return eq == std::string::npos ? 1001
                                   : size_t(std::strtoull(out.c_str() + eq + 1, nullptr, 10));
}

// A job name Slurm shows in squeue: the sweep's name, letters and digits kept.
std::string jobName(const SweepPlan& plan, const std::string& what) {
    std::string name = "so-";
    for (char c : plan.name.substr(0, 32)) name += std::isalnum((unsigned char)c) ? c : '-';
    return name + "-" + what;
}

SlurmScript script(const SweepPlan& plan, const fs::path& dir, const SlurmOptions& o,
                   const std::string& what, const std::string& array, const std::string& log,
                   const std::string& command) {
    std::string s = "#!/bin/bash\n# shadow-oracle sweep \"" + plan.name + "\": " + what +
                    " (written by `shadow-oracle sweep --slurm`, docs/sweep.md)\n";
    s += "#SBATCH --job-name=" + jobName(plan, what) + "\n";
    if (!array.empty()) s += "#SBATCH --array=" + array + "\n";
    s += "#SBATCH --output=" + (dir / "logs" / log).string() + "\n";
    if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
    // A task whose dependency can no longer be met (an oracle failed) is cancelled rather than
    // left pending for ever, so that the merge job still runs and reports it.
    s += "#SBATCH --kill-on-invalid-dep=yes\n";
    for (const std::string& a : o.sbatchArgs) s += "#SBATCH " + a + "\n";
    s += "set -euo pipefail\nexec " + command + "\n";
    return {what + ".sbatch", s};
}

// The array task's index, as a task command's `number` (SweepTaskCommand).
constexpr const char* kArrayIndex = "$SLURM_ARRAY_TASK_ID";

// A word the shell reads as itself.
bool plainWord(const std::string& a) {
    return !a.empty() && a.find_first_not_of(
                             "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                             "0123456789_./=:+-") == std::string::npos;
}

// An argv as a line of the script: words quoted where the shell would read them otherwise, the
// array index expanded by the shell.
std::string commandLine(const std::vector<std::string>& argv) {
    std::string line;
    for (const std::string& a : argv)
        line += (line.empty() ? "" : " ") + (a == kArrayIndex ? "\"" + a + "\""
                                             : plainWord(a)   ? a
                                                              : shellQuote(a));
    return line;
}

// sbatch --parsable: "JOBID" or "JOBID;CLUSTER".
std::string submit(const fs::path& file, const std::string& dependency) {
    std::string command = "sbatch --parsable";
    if (!dependency.empty()) command += " --dependency=" + dependency;
    command += " " + shellQuote(file.string());
    std::string out;
    const int rc = runCaptured(command, out);
    const std::string id = out.substr(0, out.find_first_of(";\n"));
    if (rc != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
        throw std::runtime_error("sbatch failed (exit " + std::to_string(rc) + ") for " +
                                 file.string() + (out.empty() ? "" : ": " + out));
    return id;
}

}  // namespace

std::string slurmArrayList(const std::vector<size_t>& indices) {
    std::string list;
    for (size_t i = 0; i < indices.size();) {
        size_t j = i;
        while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
        list += (list.empty() ? "" : ",") + std::to_string(indices[i]);
        if (j > i) list += "-" + std::to_string(indices[j]);
        i = j + 1;
    }
    return list;
}

SlurmSubmission submitSweepToSlurm(const SweepPlan& plan, const fs::path& dir,
                                   const SlurmOptions& o) {
    const UnfinishedTasks left = unfinishedTasks(dir, plan);
    const std::vector<size_t>&tasks = left.tasks, &scenes = left.scenes;
    SlurmSubmission r;
    r.tasks = tasks.size();
    r.scenes = scenes.size();
    r.nothingToSubmit = tasks.empty();
    if (r.nothingToSubmit) return r;
    // #SBATCH lines are split at white space: a log path there cannot hold any.
    if (dir.string().find_first_of(" \t\n") != std::string::npos)
        throwInputError(
            o.source, o.outName,
            o.slurmName + " needs a folder path without spaces (#SBATCH --output takes it)");
    if (!o.dryRun && !onPath("sbatch"))
        throwInputError(o.source, o.slurmName,
                        "sbatch is not on PATH: " + o.slurmName +
                            " needs Slurm's client commands (--dry-run prints the scripts without "
                            "them)");
    if (const size_t limit = o.dryRun ? SIZE_MAX : maxArraySize(); tasks.back() >= limit)
        throwInputError(o.source, o.slurmName,
                        "task index " + std::to_string(tasks.back()) +
                            " is not below the cluster's MaxArraySize (" + std::to_string(limit) +
                            "): raise MaxArraySize in slurm.conf or split the sweep");
    const std::string limit = o.maxConcurrent > 0 ? "%" + std::to_string(o.maxConcurrent) : "";
    r.scripts = {script(plan, dir, o, "oracles", slurmArrayList(scenes) + limit, "oracle-%a.log",
                        commandLine(o.taskCommand(true, kArrayIndex))),
                 script(plan, dir, o, "tasks", slurmArrayList(tasks) + limit, "task-%a.log",
                        commandLine(o.taskCommand(false, kArrayIndex))),
                 script(plan, dir, o, "merge", "", "merge.log", commandLine(o.mergeCommand))};
    std::error_code ec;
    fs::create_directories(dir / "slurm", ec);
    fs::create_directories(dir / "logs", ec);
    for (const SlurmScript& s : r.scripts) writeFileAtomically(dir / "slurm" / s.name, s.text);
    if (o.dryRun) return r;
    r.oraclesJob = submit(dir / "slurm" / r.scripts[0].name, "");
    r.tasksJob = submit(dir / "slurm" / r.scripts[1].name, "afterok:" + r.oraclesJob);
    r.mergeJob = submit(dir / "slurm" / r.scripts[2].name, "afterany:" + r.tasksJob);
    std::ofstream history(dir / "slurm" / "submitted.jsonl", std::ios::app);
    history << nlohmann::json{{"time", std::time(nullptr)},
                              {"oracles_job", r.oraclesJob},
                              {"tasks_job", r.tasksJob},
                              {"merge_job", r.mergeJob},
                              {"tasks", tasks}}
                   .dump()
            << "\n";
    return r;
}

}  // namespace so
