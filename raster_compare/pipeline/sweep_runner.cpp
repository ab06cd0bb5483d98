#include "raster_compare/pipeline/sweep_runner.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "core/error.h"
#include "core/json_file.h"
#include "core/scene.h"

extern char** environ;

namespace so {

namespace fs = std::filesystem;

namespace {

// One child process (the caller's command: `shadow-oracle sweep-task ...`), its output into its log
// (truncated: the log is the latest attempt's).
pid_t spawnTask(const std::vector<std::string>& args, const fs::path& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int rc = ::posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start " + args[0] + ": " + std::strerror(rc));
    return pid;
}

struct Job {
    std::vector<std::string> args;
    fs::path log;
};

// "3/12, 1 failed, 2 running": the progress callback's note.
std::string poolNote(size_t ended, size_t total, size_t failed, size_t running) {
    return std::to_string(ended) + "/" + std::to_string(total) +
           (failed ? ", " + std::to_string(failed) + " failed" : "") + ", " +
           std::to_string(running) + " running";
}

// Runs the jobs, at most `parallel` at once; returns the indices of those that failed.
std::set<size_t> runPool(const std::vector<Job>& jobs, int parallel,
                         const SweepRunCallbacks& callbacks, const std::string& stage) {
    std::map<pid_t, size_t> running;
    std::set<size_t> failed;
    size_t next = 0, ended = 0;
    // The progress moves once the ended tasks' successors run, so its note counts those running.
    const auto report = [&] {
        if (callbacks.progress)
            callbacks.progress(stage, ended, jobs.size(),
                               poolNote(ended, jobs.size(), failed.size(), running.size()));
    };
    while (next < jobs.size() || !running.empty()) {
        while (next < jobs.size() && running.size() < size_t(parallel)) {
            running[spawnTask(jobs[next].args, jobs[next].log)] = next;
            ++next;
        }
        report();
        int status = 0;
        const pid_t pid = ::waitpid(-1, &status, 0);
        if (pid < 0) break;
        const auto it = running.find(pid);
        if (it == running.end()) continue;
        const size_t k = it->second;
        running.erase(it);
        ++ended;
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            failed.insert(k);
            // A crash prints nothing of its own: the log says so, for sweep-merge's list.
            std::ofstream(jobs[k].log, std::ios::app)
                << (WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                        : "exit " + std::to_string(WEXITSTATUS(status)))
                << "\n";
        }
    }
    report();
    return failed;
}

// What killed tasks of an earlier local run left: their compare folders and temporary rows. Only
// the local runner does this: on a cluster, tasks of another submission may be writing them.
void removeLeftovers(const fs::path& dir) {
    std::error_code ec;
    fs::remove_all(dir / "work", ec);
    if (!fs::is_directory(dir / "rows")) return;
    std::vector<fs::path> temporary;
    for (const auto& e : fs::directory_iterator(dir / "rows", ec))
        if (e.path().filename().string().rfind('.', 0) == 0) temporary.push_back(e.path());
    for (const fs::path& p : temporary) fs::remove(p, ec);
}

// An image re-rendered since its row was made (another hash of the image and its cost file, or
// gone) makes the row stale: removed, so that the task runs again (and fails, saying why, when
// the image is gone).
void dropStaleImageRows(const SweepPlan& plan, const fs::path& dir,
                        const SweepRunCallbacks& callbacks) {
    size_t removed = 0;
    for (const SweepTask& t : plan.tasks) {
        if (t.image.empty()) continue;
        const fs::path row = sweepRowPath(dir, t);
        std::ifstream in(row);
        if (!in) continue;
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        in.close();
        if (imageRowIsStale(j, t)) removed += fs::remove(row);
    }
    if (removed && callbacks.notice)
        callbacks.notice("sweep: " + std::to_string(removed) +
                         " images changed since their rows were made: those rows removed, their "
                         "tasks run again");
}

}  // namespace

void dropStaleRows(const SweepPlan& plan, const fs::path& dir, const SweepRunCallbacks& callbacks) {
    const fs::path path = sweepSceneHashesPath(dir);
    nlohmann::json hashes = nlohmann::json::object();
    if (std::ifstream in(path); in) hashes = nlohmann::json::parse(in, nullptr, false);
    if (!hashes.is_object()) hashes = nlohmann::json::object();
    for (size_t si = 0; si < plan.scenes.size(); ++si) {
        std::string hash;
        try {
            hash = loadScene(plan.scenes[si].path.string()).contentHash;
        } catch (const InputError&) {
            continue;
        }
        const std::string key = std::to_string(si);
        if (hashes.contains(key) && hashes[key] != hash) {
            size_t removed = 0;
            for (const SweepTask& t : plan.tasks)
                if (t.scene == si) removed += fs::remove(sweepRowPath(dir, t));
            if (callbacks.notice)
                callbacks.notice("sweep: " + plan.scenes[si].name +
                                 " changed since its rows were made: " + std::to_string(removed) +
                                 " rows removed, its tasks run again");
        }
        hashes[key] = hash;
    }
    writeFileAtomically(path, hashes.dump(1) + "\n");
    dropStaleImageRows(plan, dir, callbacks);
}

void runSweepLocally(const SweepPlan& plan, const fs::path& dir, int jobs,
                     const SweepTaskCommand& command, const SweepRunCallbacks& callbacks) {
    SO_CHECK(jobs >= 1);
    removeLeftovers(dir);
    std::vector<Job> oracles, tasks;
    const UnfinishedTasks left = unfinishedTasks(dir, plan);
    const std::vector<size_t>& sceneList = left.scenes;
    std::error_code ec;
    fs::create_directories(dir / "logs", ec);
    if (callbacks.notice)
        callbacks.notice(
            "sweep " + plan.name + ": " + std::to_string(plan.tasks.size() - left.tasks.size()) +
            " of " + std::to_string(plan.tasks.size()) + " tasks already finished, " +
            std::to_string(left.tasks.size()) + " to run over " + std::to_string(sceneList.size()) +
            " scenes, " + std::to_string(jobs) + " at once");
    for (size_t s : sceneList)
        oracles.push_back({command(true, std::to_string(s)), sweepOracleLogPath(dir, s)});
    std::set<size_t> badScenes;
    for (size_t k : runPool(oracles, jobs, callbacks, "oracles")) badScenes.insert(sceneList[k]);
    for (size_t i : left.tasks)
        if (!badScenes.count(plan.tasks[i].scene))  // its oracle's log says why
            tasks.push_back({command(false, std::to_string(i)), sweepTaskLogPath(dir, i)});
        else
            fs::remove(sweepTaskLogPath(dir, i), ec);
    runPool(tasks, jobs, callbacks, "tasks");
    fs::remove(dir / "work", ec);  // empty now, unless a task failed half-way
}

}  // namespace so
