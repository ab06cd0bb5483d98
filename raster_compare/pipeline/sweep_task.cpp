#include "raster_compare/pipeline/sweep_task.h"

#include <chrono>
#include <iostream>

#include "cli/compare_command.h"
#include "cli/output.h"
#include "core/error.h"
#include "core/visibility_image.h"
#include "oracle/oracle_cache.h"
#include "oracle/trace_options.h"
#include "raster_compare/pipeline/sweep_spec.h"

namespace so {

namespace fs = std::filesystem;

namespace {

// The spec's oracle settings over compare's defaults: the same options, so the same cache key, in
// the oracle task and in every technique task of the scene.
OracleOptions oracleOptions(const SweepOracleSettings& s) {
    OracleOptions o;
    o.width = s.width;
    o.height = s.height;
    applyTraceOptions(s.values, {"sweep.json", /*cliNames=*/false, "oracle.", false}, o);
    return o;
}

// The oracle of scene S into DIR/oracles (oracle_cache.h: content-addressed by the scene's hash
// and the oracle options, so a present and valid entry is loaded, never traced again).
int runOracleTask(const fs::path& dir, const SweepPlan& plan, size_t si) {
    const SweepScene& s = plan.scenes[si];
    const Scene scene = loadScene(s.path.string());
    printSceneWarnings(s.path.string(), scene);
    const OracleOptions options = oracleOptions(plan.settings.oracle);
    const CachedOracle oracle =
        traceOrLoad(scene, options, {sweepOracleCacheDir(dir), /*use=*/true});
    printWarnings(oracle.warnings);
    std::cout << "oracle of " << s.name << ": " << (oracle.fromCache ? "present" : "traced") << " ("
              << oracle.key << ")\n";
    return 0;
}

// The row of a task (docs/sweep.md, "Rows"): the task, and its setting's entry of compare's
// metrics.json with what made it.
nlohmann::json taskRow(const SweepPlan& plan, const SweepTask& t, size_t index,
                       const CompareOptions& c, const CompareRun& run, double seconds,
                       const std::string& imageHash) {
    nlohmann::json swept = nlohmann::json::object();
    for (const auto& [k, v] : t.swept) swept[k] = v;
    SO_CHECK_EQ(run.comparison.rows.size(), size_t(1));
    nlohmann::json result = rowJson(run.comparison.rows[0]);
    const nlohmann::json made =
        metricsHeaderJson(run.scene, c.scenePath, run.oracle, run.comparison, c.boundaryRadius);
    nlohmann::json taskJson = {
        {"index", index},           {"id", t.id},       {"scene", plan.scenes[t.scene].name},
        {"technique", t.technique}, {"label", t.label}, {"swept", swept}};
    if (!t.image.empty()) {
        taskJson["image"] = {{"path", t.image}, {"hash", imageHash}};
        // The grid's values are the image's parameters too (the cost file's, where it has them,
        // come first: they are the renderer's own account).
        for (const std::string& s : t.settings) {
            const size_t eq = s.find('=');
            const std::string key = s.substr(0, eq);
            if (!result["parameters"].contains(key))
                result["parameters"][key] = std::stod(s.substr(eq + 1));
        }
    }
    return {{"sweep_format", kSweepFormat},
            {"task", taskJson},
            {"seconds", seconds},
            {"tool", made.at("tool")},
            {"gl", made.at("gl")},
            {"scene", made.at("scene")},
            {"options", made.at("options")},
            {"oracle", {{"key", run.oracle.key}, {"cached", run.oracle.fromCache}}},
            {"result", result}};
}

int runTechniqueTask(const fs::path& dir, const SweepPlan& plan, const SweepTask& t, size_t index) {
    const fs::path row = sweepRowPath(dir, t);
    if (fs::exists(row)) {
        std::cout << "task " << index << " (" << t.id << ") already finished: " << row.string()
                  << "\n";
        return 0;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const fs::path work = dir / "work" / t.id;
    std::error_code ec;
    fs::remove_all(work, ec);  // what a killed run of this task left
    CompareOptions c;
    c.scenePath = plan.scenes[t.scene].path.string();
    if (plan.settings.keepOutputs) c.outDir = work.string();  // else no files but the row
    // The image's hash before it is read: a renderer rewriting it meanwhile makes the row stale.
    std::string imageHash;
    if (t.image.empty()) {
        c.techniques = {t.label};
    } else {
        imageHash = imageInputsHash(t.image);
        c.images = {makeImageSpec(t.label, t.image)};
        c.imageEncoding = parseImageEncoding(t.encoding, "tasks.jsonl", "encoding");
    }
    c.oracle = oracleOptions(plan.settings.oracle);
    c.raster.width = plan.settings.oracle.width;
    c.raster.height = plan.settings.oracle.height;
    c.raster.frames = plan.settings.frames;
    c.cacheDir = sweepOracleCacheDir(dir);
    c.boundaryRadius = plan.settings.boundaryRadius;
    c.writeReport = false;
    CompareRun run = compareScene(c, printingCallbacks());
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const nlohmann::json taskRowJson = taskRow(plan, t, index, c, run, seconds, imageHash);
    if (plan.settings.keepOutputs) {
        const int rc = writeCompareOutputs(c, run);
        if (rc != 0) return rc;
        fs::remove_all(dir / "outputs" / t.id, ec);
        fs::create_directories(dir / "outputs", ec);
        fs::rename(work, dir / "outputs" / t.id, ec);
    }
    // The row last, atomically: it is what marks the task done.
    writeFileAtomically(row, taskRowJson.dump() + "\n");
    std::cout << "task " << index << " (" << t.id << ", " << t.label << " on "
              << plan.scenes[t.scene].name << ") finished in " << seconds << " s\n";
    return 0;
}

}  // namespace

int runSweepTask(const SweepTaskOptions& options) {
    const fs::path dir = options.dir;
    const SweepPlan plan = readPlan(dir, /*withTasks=*/false);
    if ((options.index >= 0) == (options.oracle >= 0))
        throwInputError("command line", "--index", "give exactly one of --index K and --oracle S");
    if (options.oracle >= 0) {
        if (size_t(options.oracle) >= plan.scenes.size())
            throwInputError("command line", "--oracle",
                            std::to_string(options.oracle) + " is out of range: the sweep has " +
                                std::to_string(plan.scenes.size()) + " scenes");
        return runOracleTask(dir, plan, size_t(options.oracle));
    }
    if (size_t(options.index) >= plan.taskCount)
        throwInputError("command line", "--index",
                        std::to_string(options.index) + " is out of range: the sweep has " +
                            std::to_string(plan.taskCount) + " tasks");
    const size_t index = size_t(options.index);
    return runTechniqueTask(dir, plan, readPlanTask(dir, plan, index), index);
}

}  // namespace so
