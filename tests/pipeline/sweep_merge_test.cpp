// The merge of a sweep (raster_compare/pipeline/sweep_merge.h, docs/sweep.md): the rows of the
// finished tasks into metrics.csv, metrics_wide.csv, metrics.json and report.html, and each task
// without a fresh row listed with why. Rows made by hand, no GL. Label "pipeline".
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "raster_compare/pipeline/sweep_merge.h"
#include "sweep_folder.h"

namespace so {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string fileText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A task's row as sweep-task writes it, with one light and the metrics given.
void writeRow(const test::SweepFolder& f, size_t index, const json& metrics,
              const std::string& sceneHash = "h") {
    const SweepTask& t = f.plan().tasks[index];
    json swept = json::object();
    for (const auto& [k, v] : t.swept) swept[k] = v;
    const json row = {
        {"scene", {{"hash", sceneHash}}},
        {"task", {{"id", t.id}, {"swept", swept}}},
        {"oracle", {{"key", "oracle-" + std::to_string(t.scene)}}},
        {"gl", {{"renderer", "test renderer"}}},
        {"result",
         {{"parameters", {{"alpha", t.swept.at(0).second}}}, {"lights", {{"sun", metrics}}}}}};
    const fs::path path = sweepRowPath(f.dir(), t);
    fs::create_directories(path.parent_path());
    std::ofstream(path) << row.dump();
}

TEST(SweepMerge, FinishedRowsBecomeTheTablesAndTheRestAreListedWithWhy) {
    test::SweepFolder f("sweep_merge_test");
    const SweepPlan& plan = f.plan();
    ASSERT_EQ(plan.tasks.size(), 4u);
    writeRow(f, 0, {{"mae", 0.125}, {"cost", {{"frame_ms", 2.5}}}});
    writeRow(f, 2, {{"mae", 0.5}, {"cost", {{"frame_ms", 1.5}}}});
    fs::create_directories(f.dir() / "logs");
    std::ofstream(sweepTaskLogPath(f.dir(), 3)) << "starting\nerror: the GL context failed\n\n";

    const SweepMerge m = mergeSweep(f.dir(), /*imagesChecked=*/true);
    EXPECT_EQ(m.name, "pipe test");
    EXPECT_EQ(m.tasks, 4u);
    EXPECT_EQ(m.finished, 2u);
    EXPECT_TRUE(m.warnings.empty());
    ASSERT_EQ(m.failed.size(), 2u);
    EXPECT_EQ(m.failed[0].task, plan.tasks[1].id);
    EXPECT_EQ(m.failed[0].reason, "not run");
    EXPECT_EQ(m.failed[1].task, plan.tasks[3].id);
    EXPECT_EQ(m.failed[1].reason, "error: the GL context failed") << "the log's last line";
    EXPECT_EQ(m.failed[1].log, "logs/task-3.log");

    const std::string csv = fileText(m.metricsCsv);
    const std::string a = plan.scenes[plan.tasks[0].scene].name;
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "scene,light,technique,label,metric,value,task,param.alpha");
    EXPECT_NE(csv.find(a + ",sun,shadow,shadow:alpha=1,mae,0.125," + plan.tasks[0].id + ",1\n"),
              std::string::npos)
        << csv;
    EXPECT_NE(csv.find(",sun,shadow,shadow:alpha=1,cost.frame_ms,1.5," + plan.tasks[2].id + ",1\n"),
              std::string::npos)
        << csv;
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5) << "a header and 2 rows x 2 metrics";

    const std::string wide = fileText(m.metricsWideCsv);
    // The metrics in the order the JSON objects keep them, sorted by key (docs/metrics.md).
    EXPECT_EQ(wide.substr(0, wide.find('\n')),
              "task,scene,light,technique,label,param.alpha,cost.frame_ms,mae");

    const json j = json::parse(fileText(m.metricsJson));
    EXPECT_EQ(j.at("tasks"), 4);
    EXPECT_EQ(j.at("finished"), 2);
    EXPECT_EQ(j.at("failed").size(), 2u);
    EXPECT_EQ(j.at("results").size(), 2u);
    EXPECT_EQ(j.at("results")[0].at("oracle_key"), "oracle-0");
    EXPECT_EQ(j.at("results")[0].at("task").at("id"), plan.tasks[0].id);

    const std::string report = fileText(m.report);
    EXPECT_NE(report.find("pipe test"), std::string::npos);
    EXPECT_NE(report.find("test renderer"), std::string::npos) << "who measured the times";
}

TEST(SweepMerge, AnUnreadableRowIsAWarningAndNotFinished) {
    test::SweepFolder f("sweep_merge_bad_row_test");
    writeRow(f, 0, {{"mae", 0.25}});
    const fs::path bad = sweepRowPath(f.dir(), f.plan().tasks[1]);
    fs::create_directories(bad.parent_path());
    std::ofstream(bad) << "{\"scene\": ";
    const SweepMerge m = mergeSweep(f.dir(), true);
    EXPECT_EQ(m.finished, 1u);
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_NE(m.warnings[0].find(bad.string()), std::string::npos) << m.warnings[0];
    EXPECT_NE(m.warnings[0].find("task 1 counted as not finished"), std::string::npos);
    EXPECT_EQ(m.failed.size(), 3u);
}

TEST(SweepMerge, ARowOfAnotherSceneContentIsStale) {
    test::SweepFolder f("sweep_merge_stale_test");
    writeRow(f, 0, {{"mae", 0.25}}, "old");
    writeRow(f, 1, {{"mae", 0.25}}, "new");
    std::ofstream(sweepSceneHashesPath(f.dir())) << R"({"0": "new"})";
    const SweepMerge m = mergeSweep(f.dir(), true);
    EXPECT_EQ(m.finished, 1u);
    ASSERT_EQ(m.failed.size(), 3u);
    EXPECT_EQ(m.failed[0].task, f.plan().tasks[0].id);
    EXPECT_EQ(m.failed[0].reason,
              "stale: its scene changed since the row was made (rerun the sweep)");
}

TEST(SweepMerge, AMalformedRowIsAnInputErrorNamingTheRows) {
    test::SweepFolder f("sweep_merge_malformed_test");
    const fs::path path = sweepRowPath(f.dir(), f.plan().tasks[0]);
    fs::create_directories(path.parent_path());
    std::ofstream(path) << R"({"scene": {"hash": "h"}, "result": {"lights": {}}})";
    try {
        mergeSweep(f.dir(), true);
        FAIL() << "a row without its parameters was merged";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() + ": result.parameters: missing");
    }
}

}  // namespace
}  // namespace so
