// The Slurm scripts of a sweep (raster_compare/pipeline/slurm.h, docs/sweep.md "On a Slurm
// cluster"), written in a dry run: what each job runs, its array of the unfinished tasks, and the
// options every script carries. Needs no Slurm. Label "pipeline".
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "raster_compare/pipeline/slurm.h"
#include "sweep_folder.h"

namespace so {
namespace {

namespace fs = std::filesystem;

std::string fileText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(Slurm, ArrayListsJoinRuns) {
    EXPECT_EQ(slurmArrayList({}), "");
    EXPECT_EQ(slurmArrayList({5}), "5");
    EXPECT_EQ(slurmArrayList({0, 1, 2, 3, 7, 9, 10}), "0-3,7,9-10");
    EXPECT_EQ(slurmArrayList({2, 4, 6}), "2,4,6");
}

// The command the program gives both runners (cli/sweep_command.cpp): `sweep-task DIR --oracle S`
// or `--index K`, the array index as the shell word.
SweepTaskCommand taskCommand(const std::string& exe, const fs::path& dir) {
    return [exe, dir](bool oracle, const std::string& number) {
        return std::vector<std::string>{exe, "sweep-task", dir.string(),
                                        oracle ? "--oracle" : "--index", number};
    };
}

TEST(Slurm, DryRunWritesThreeScriptsOverTheUnfinishedTasks) {
    test::SweepFolder folder("slurm_test");
    const SweepPlan& plan = folder.plan();
    ASSERT_EQ(plan.tasks.size(), 4u);  // 2 scenes x alpha 1, 2
    // Task 0 has its row: only 1-3 are submitted, and both scenes' oracles (tasks 2, 3 are b's).
    const fs::path row = sweepRowPath(folder.dir(), plan.tasks[0]);
    fs::create_directories(row.parent_path());
    std::ofstream(row) << "{}";

    SlurmOptions o;
    o.partition = "gpu";
    o.maxConcurrent = 3;
    o.sbatchArgs = {"--time=00:10:00", "--gres=gpu:1"};
    o.dryRun = true;
    o.taskCommand = taskCommand("/opt/so/bin/shadow-oracle", folder.dir());
    o.mergeCommand = {"/opt/so/bin/shadow-oracle", "sweep-merge", folder.dir().string()};
    const SlurmSubmission s = submitSweepToSlurm(plan, folder.dir(), o);
    EXPECT_FALSE(s.nothingToSubmit);
    EXPECT_EQ(s.tasks, 3u);
    EXPECT_EQ(s.scenes, 2u);
    EXPECT_TRUE(s.oraclesJob.empty() && s.tasksJob.empty() && s.mergeJob.empty())
        << "a dry run submits nothing";
    ASSERT_EQ(s.scripts.size(), 3u);
    // The folder as the script's shell reads it: quoted only where it has to be (slurm.cpp).
    const std::string path = folder.dir().string();
    const bool plain = path.find_first_not_of(
                           "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                           "0123456789_./=:+-") == std::string::npos;
    const std::string dir = plain ? path : "'" + path + "'";
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"oracles.sbatch", "#SBATCH --array=0-1%3\n"},
        {"tasks.sbatch", "#SBATCH --array=1-3%3\n"},
        {"merge.sbatch", ""}};
    const std::vector<std::string> commands = {
        "exec /opt/so/bin/shadow-oracle sweep-task " + dir + " --oracle \"$SLURM_ARRAY_TASK_ID\"\n",
        "exec /opt/so/bin/shadow-oracle sweep-task " + dir + " --index \"$SLURM_ARRAY_TASK_ID\"\n",
        "exec /opt/so/bin/shadow-oracle sweep-merge " + dir + "\n"};
    for (size_t i = 0; i < 3; ++i) {
        const SlurmScript& script = s.scripts[i];
        SCOPED_TRACE(script.name);
        EXPECT_EQ(script.name, expected[i].first);
        EXPECT_EQ(script.text.rfind("#!/bin/bash\n", 0), 0u);
        if (expected[i].second.empty())
            EXPECT_EQ(script.text.find("--array"), std::string::npos);
        else
            EXPECT_NE(script.text.find(expected[i].second), std::string::npos) << script.text;
        for (const char* line :
             {"#SBATCH --partition=gpu\n", "#SBATCH --time=00:10:00\n", "#SBATCH --gres=gpu:1\n",
              "#SBATCH --kill-on-invalid-dep=yes\n", "#SBATCH --job-name=so-pipe-test-"})
            EXPECT_NE(script.text.find(line), std::string::npos) << line << " in\n" << script.text;
        EXPECT_NE(script.text.find(commands[i]), std::string::npos) << script.text;
        EXPECT_EQ(fileText(folder.dir() / "slurm" / script.name), script.text)
            << "the script returned is the script written";
    }
}

TEST(Slurm, NothingToSubmitWhenEveryTaskHasItsRow) {
    test::SweepFolder folder("slurm_done_test");
    for (const SweepTask& t : folder.plan().tasks) {
        const fs::path row = sweepRowPath(folder.dir(), t);
        fs::create_directories(row.parent_path());
        std::ofstream(row) << "{}";
    }
    SlurmOptions o;
    o.dryRun = true;
    o.taskCommand = taskCommand("shadow-oracle", folder.dir());
    o.mergeCommand = {"shadow-oracle", "sweep-merge", folder.dir().string()};
    const SlurmSubmission s = submitSweepToSlurm(folder.plan(), folder.dir(), o);
    EXPECT_TRUE(s.nothingToSubmit);
    EXPECT_EQ(s.tasks, 0u);
    EXPECT_TRUE(s.scripts.empty());
    EXPECT_FALSE(fs::exists(folder.dir() / "slurm"));
}

}  // namespace
}  // namespace so
