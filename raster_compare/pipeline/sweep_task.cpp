#include "raster_compare/pipeline/sweep_task.h"

#include <chrono>

#include "core/error.h"
#include "core/visibility_image.h"
#include "oracle/oracle_cache.h"
#include "oracle/trace_options.h"
#include "raster_compare/gl/render/raster_options.h"

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

void warnAll(const SweepTaskCallbacks& callbacks, const std::vector<std::string>& warnings,
             const std::string& prefix = "") {
    if (!callbacks.compare.warning) return;
    for (const std::string& w : warnings) callbacks.compare.warning(prefix + w);
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

// compare's options for a task: the spec's oracle and frames, the sweep's oracle cache, its
// folder in DIR/work when the spec keeps outputs.
CompareOptions taskCompareOptions(const fs::path& dir, const SweepPlan& plan, const SweepTask& t,
                                  std::string& imageHash) {
    CompareOptions c;
    c.scenePath = plan.scenes[t.scene].path.string();
    if (plan.settings.keepOutputs) c.outDir = (dir / "work" / t.id).string();
    if (t.image.empty()) {
        c.techniques = {t.label};
    } else {
        // The image's hash before it is read: a renderer rewriting it meanwhile makes the row
        // stale.
        imageHash = imageInputsHash(t.image);
        c.images = {makeImageSpec(t.label, t.image)};
        c.imageEncoding = parseImageEncoding(t.encoding, "tasks.jsonl", "encoding");
    }
    c.oracle = oracleOptions(plan.settings.oracle);
    c.raster.width = plan.settings.oracle.width;
    c.raster.height = plan.settings.oracle.height;
    const std::string spec = plan.specFile.string();
    applyRasterOptions(plan.settings.raster, {spec, false, "", false}, c.raster);
    applyCompareOptions(plan.settings.compare, {spec, false, "", false}, c);
    c.cacheDir = sweepOracleCacheDir(dir);
    c.writeReport = false;
    // Errors name the spec's keys: a task runs what the spec says, not a command line.
    c.names = {spec,          "techniques",    "images",           "points",
               "frames_path", "oracle.verify", "width and height", "keep_outputs",
               "sequence",    "converge"};
    return c;
}

}  // namespace

SweepOracleTaskResult runSweepOracleTask(const fs::path& dir, const SweepPlan& plan, size_t si,
                                         const SweepTaskCallbacks& callbacks) {
    SO_CHECK(si < plan.scenes.size());
    const SweepScene& s = plan.scenes[si];
    const Scene scene = loadScene(s.path.string());
    warnAll(callbacks, scene.stats.warnings, s.path.string() + ": ");
    const OracleOptions options = oracleOptions(plan.settings.oracle);
    const CachedOracle oracle =
        traceOrLoad(scene, options, {sweepOracleCacheDir(dir), /*use=*/true});
    warnAll(callbacks, oracle.warnings);
    return {s.name, oracle.fromCache, oracle.key};
}

SweepTechniqueTaskResult runSweepTechniqueTask(const fs::path& dir, const SweepPlan& plan,
                                               size_t index, const SweepTaskCallbacks& callbacks) {
    SO_CHECK(index < plan.taskCount);
    const SweepTask t = readPlanTask(dir, plan, index);
    SweepTechniqueTaskResult result;
    result.id = t.id;
    result.label = t.label;
    result.scene = plan.scenes[t.scene].name;
    result.row = sweepRowPath(dir, t);
    if (fs::exists(result.row)) {
        result.alreadyFinished = true;
        return result;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const fs::path work = dir / "work" / t.id;
    std::error_code ec;
    fs::remove_all(work, ec);  // what a killed run of this task left
    std::string imageHash;
    const CompareOptions c = taskCompareOptions(dir, plan, t, imageHash);
    CompareRun run = compareScene(c, callbacks.compare);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const nlohmann::json taskRowJson = taskRow(plan, t, index, c, run, result.seconds, imageHash);
    if (plan.settings.keepOutputs) {
        const CompareOutputFiles files = writeCompareRun(c, run);
        if (callbacks.outputsWritten) callbacks.outputsWritten(c, run, files);
        if (run.oracle.stats.verified() && run.oracle.stats.disagreements() > 0) {
            result.exitCode = 3;
            return result;
        }
        fs::remove_all(dir / "outputs" / t.id, ec);
        fs::create_directories(dir / "outputs", ec);
        fs::rename(work, dir / "outputs" / t.id, ec);
    }
    // The row last, atomically: it is what marks the task done.
    writeFileAtomically(result.row, taskRowJson.dump() + "\n");
    return result;
}

}  // namespace so
