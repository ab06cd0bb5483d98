// The sweep through a real Slurm (label slurm): scripts/slurm-local's one-node cluster runs the
// oracle array, the task array and the merge job; the merged table must equal a local `--jobs 2`
// run of the same spec, timings aside; after two rows are lost, submitting again submits just those
// two. Skips, saying why, where no cluster answers (CI starts one: .ci/run).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "sweep_test_util.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;

std::string shell(const std::string& command, int* rc = nullptr) {
    std::string out;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return out;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    const int status = ::pclose(pipe);
    if (rc) *rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return out;
}

// SLURM_CONF of the local cluster when it answers; empty (and why) when not.
std::string localCluster(std::string& why) {
    int rc = 0;
    const std::string out =
        shell(std::string(SO_SOURCE_DIR) + "/scripts/slurm-local status 2>&1", &rc);
    std::smatch m;
    if (rc != 0 || !std::regex_search(out, m, std::regex("export SLURM_CONF=(\\S+)"))) {
        why = out.empty() ? "scripts/slurm-local status failed" : out;
        return "";
    }
    return m[1];
}

// Waits for the merge job the sweep printed to leave the queue; false after `seconds`.
bool waitForJob(const std::string& job, int seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
        int rc = 0;
        const std::string out = shell("squeue -h -j " + job + " -t PD,R,CG,CF 2>/dev/null", &rc);
        if (rc == 0 && out.find_first_not_of(" \n") == std::string::npos) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    return false;
}

std::string mergeJob(const std::string& log) {
    std::smatch m;
    return std::regex_search(log, m, std::regex("merge job (\\d+)")) ? std::string(m[1]) : "";
}

TEST(SlurmSweep, EqualsALocalRunAndResubmitsOnlyWhatIsMissing) {
    REQUIRE_GL();
    std::string why;
    const std::string conf = localCluster(why);
    if (conf.empty())
        GTEST_SKIP() << "no local Slurm cluster answers (start one with scripts/slurm-local "
                        "start): "
                     << why;
    ::setenv("SLURM_CONF", conf.c_str(), 1);
    const fs::path dir = fs::temp_directory_path() / ("so_slurm_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path spec = dir / "spec.json";
    // 2 scenes x 6 settings.
    std::ofstream(spec) << R"({"sweep_format": 1, "name": "slurm-test",
        "scenes": [")" << SO_SCENES_DIR
                        << R"(/contact_box.scene.json", ")" << SO_SCENES_DIR
                        << R"(/spot_objects.scene.json"],
        "width": 64, "height": 48, "frames": 1,
        "techniques": [{"name": "slope-bias", "params": {"alpha": [0, 1, 2], "min": [0, 0.5],
                                                         "resolution": 512}}]})";
    std::string log;
    const std::string slurmOut = (dir / "slurm").string(), localOut = (dir / "local").string();
    ASSERT_EQ(runCli("sweep " + spec.string() + " --out " + slurmOut +
                         " --slurm --max-concurrent 2 --sbatch-arg=--time=10",
                     &log),
              0)
        << log;
    std::string job = mergeJob(log);
    ASSERT_FALSE(job.empty()) << log;
    ASSERT_TRUE(waitForJob(job, 600)) << "the merge job " << job << " did not end in 10 minutes";
    ASSERT_TRUE(fs::exists(fs::path(slurmOut) / "metrics.json"))
        << readBytes(fs::path(slurmOut) / "logs" / "merge.log");
    ASSERT_EQ(runCli("sweep " + spec.string() + " --out " + localOut + " --jobs 2 --quiet", &log),
              0)
        << log;
    const auto slurm = mergedResults(slurmOut), local = mergedResults(localOut);
    EXPECT_EQ(slurm.size(), 12u);
    EXPECT_EQ(slurm, local);
    EXPECT_EQ(csvWithoutTimings(fs::path(slurmOut) / "metrics.csv"),
              csvWithoutTimings(fs::path(localOut) / "metrics.csv"));
    EXPECT_NE(readBytes(fs::path(slurmOut) / "slurm" / "tasks.sbatch").find("#SBATCH --time=10"),
              std::string::npos);

    // Two rows lost: the next submission's array holds just those two tasks. They are chosen by
    // plan index, not by id (ids hash the scene's path, which differs between checkouts), and
    // not adjacent, so the array is a list rather than a range.
    size_t removed = 0;
    for (const auto& [id, result] : slurm) {
        const size_t index = result["task"]["index"].get<size_t>();
        if (index == 1 || index == 7) {
            fs::remove(fs::path(slurmOut) / "rows" / (id + ".json"));
            ++removed;
        }
    }
    ASSERT_EQ(removed, 2u);
    ASSERT_EQ(runCli("sweep " + spec.string() + " --out " + slurmOut + " --slurm --dry-run", &log),
              0);
    EXPECT_NE(log.find("#SBATCH --array=1,7\n"), std::string::npos) << log;
    ASSERT_EQ(runCli("sweep " + spec.string() + " --out " + slurmOut + " --slurm", &log), 0) << log;
    EXPECT_NE(log.find("(2 of 12 tasks)"), std::string::npos) << log;
    job = mergeJob(log);
    ASSERT_TRUE(waitForJob(job, 600));
    EXPECT_EQ(mergedResults(slurmOut), local);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so
