#include "raster_compare/pipeline/sweep_merge.h"

#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/tool_info.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/compare/sweep_report.h"
#include "raster_compare/pipeline/csv_table.h"
#include "raster_compare/pipeline/row_parameters.h"
#include "raster_compare/pipeline/sweep_spec.h"

namespace so {

namespace fs = std::filesystem;

namespace {

// The last line of a log that says something (an error is printed last), capped.
std::string lastLine(const fs::path& log) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return printable(last, 200);
}

// Why a task has no row: what its log (or its scene's oracle log) ended with, or "not run".
SweepFailure failure(const fs::path& dir, const SweepPlan& plan, size_t index) {
    const SweepTask& t = plan.tasks[index];
    SweepFailure f{t.id, plan.scenes[t.scene].name, t.label, "not run", ""};
    const fs::path log = sweepTaskLogPath(dir, index);
    const fs::path oracleLog = sweepOracleLogPath(dir, t.scene);
    if (fs::exists(log)) {
        f.log = log.lexically_relative(dir).generic_string();
        const std::string last = lastLine(log);
        f.reason = last.empty() ? "failed or still running (empty log)" : last;
    } else if (fs::exists(oracleLog) && lastLine(oracleLog).rfind("oracle of ", 0) != 0) {
        f.log = oracleLog.lexically_relative(dir).generic_string();
        f.reason = "its scene's oracle failed: " + lastLine(oracleLog);
    }
    return f;
}

// Every task's row, by plan index; a row that does not parse counts as not finished.
struct Rows {
    std::vector<std::pair<size_t, nlohmann::json>> done;
    std::vector<SweepFailure> failed;
};

// A row made from another content of its scene than the sweep last recorded
// (scene_hashes.json): stale, not finished.
bool stale(const nlohmann::json& row, const nlohmann::json& hashes, size_t scene) {
    const std::string key = std::to_string(scene);
    return hashes.is_object() && hashes.contains(key) &&
           row.at("scene").at("hash") != hashes.at(key);
}

Rows readRows(const fs::path& dir, const SweepPlan& plan, bool imagesChecked,
              std::vector<std::string>& warnings) {
    Rows rows;
    nlohmann::json hashes;
    if (std::ifstream in(sweepSceneHashesPath(dir)); in)
        hashes = nlohmann::json::parse(in, nullptr, false);
    for (size_t i = 0; i < plan.tasks.size(); ++i) {
        const fs::path path = sweepRowPath(dir, plan.tasks[i]);
        std::ifstream in(path);
        if (in) {
            try {
                nlohmann::json row = nlohmann::json::parse(in);
                const bool sceneChanged = stale(row, hashes, plan.tasks[i].scene);
                const bool imageChanged =
                    !sceneChanged && !imagesChecked && imageRowIsStale(row, plan.tasks[i]);
                if (!sceneChanged && !imageChanged) {
                    rows.done.emplace_back(i, std::move(row));
                    continue;
                }
                SweepFailure f = failure(dir, plan, i);
                f.reason = std::string("stale: its ") + (sceneChanged ? "scene" : "image") +
                           " changed since the row was made (rerun the sweep)";
                rows.failed.push_back(f);
                continue;
            } catch (const nlohmann::json::exception& e) {
                warnings.push_back(path.string() + ": unreadable row, task " + std::to_string(i) +
                                   " counted as not finished: " + e.what());
            }
        }
        rows.failed.push_back(failure(dir, plan, i));
    }
    return rows;
}

// The swept parameters of the whole sweep, in first-seen order: the extra columns.
std::vector<std::string> sweptColumns(const SweepPlan& plan) {
    std::vector<std::string> columns;
    std::set<std::string> seen;
    for (const SweepTask& t : plan.tasks)
        for (const auto& [k, v] : t.swept)
            if (seen.insert(k).second) columns.push_back(k);
    return columns;
}

struct Tables {
    std::ostringstream csv;
    WideCsv wide;
    nlohmann::json results = nlohmann::json::array();
    SweepReportInput report;
    std::set<std::string> renderers;
};

// One light of one task's row into the long and wide tables and the report's rows.
void addLight(Tables& t, const SweepPlan& plan, const std::vector<std::string>& swept,
              const SweepTask& task, const nlohmann::json& parameters, const std::string& light,
              const nlohmann::json& metrics, const JsonReader& in) {
    const std::string& scene = plan.scenes[task.scene].name;
    std::vector<std::pair<std::string, std::string>> wide = {{"task", task.id},
                                                             {"scene", scene},
                                                             {"light", light},
                                                             {"technique", task.technique},
                                                             {"label", task.label}};
    std::string params;
    for (const std::string& name : swept) {
        std::string value;
        for (const auto& [k, v] : task.swept)
            if (k == name) value = shortestNumber(v);
        params += "," + value;
    }
    // The wide table as compare's: every parameter of the setting, defaults included.
    for (const auto& [name, value] : parameters.items())
        wide.emplace_back("param." + name, value.dump());
    // The report's row: the task's setting and this light's metrics, read back typed.
    SweepRow row{task.id, scene, {}, {}};
    row.result.label = task.label;
    row.result.technique = task.technique;
    row.result.parameters = typedParameters(task.technique, parameters);
    row.result.lights.push_back(
        readLightRow(metrics, light, in, "result.lights." + printable(light, 60)));
    for (const auto& [name, value] : task.swept)
        row.swept.emplace_back(name, typedParamValue(task.technique, name, value));
    for (const auto& [metric, value] : flatMetrics(metrics)) {
        const std::string text = value.is_null() ? "" : value.dump();
        t.csv << csvField(scene) << ',' << csvField(light) << ',' << csvField(task.technique) << ','
              << csvField(task.label) << ',' << metric << ',' << text << ',' << task.id << params
              << "\n";
        wide.emplace_back(metric, text);
    }
    t.wide.add(wide);
    t.report.rows.push_back(std::move(row));
}

// A row's shape is checked by the one reader of JSON (core/json_reader.h), naming the row's file
// and field; what lies deeper (a metric's value) is caught by mergeSweep as a malformed row.
void addRow(Tables& t, const SweepPlan& plan, const std::vector<std::string>& swept, size_t index,
            const nlohmann::json& row, const JsonReader& in) {
    const SweepTask& task = plan.tasks[index];
    const nlohmann::json& result = in.at(row, "", "result");
    const nlohmann::json& lights = in.at(result, "result", "lights");
    in.requireObject(lights, "result.lights");
    const nlohmann::json& parameters = in.at(result, "result", "parameters");
    in.requireObject(parameters, "result.parameters");
    for (const auto& [light, metrics] : lights.items())
        addLight(t, plan, swept, task, parameters, light, metrics, in);
    nlohmann::json r = result;
    r["task"] = {{"index", index}, {"id", task.id}, {"scene", plan.scenes[task.scene].name}};
    r["swept"] = in.at(in.at(row, "", "task"), "task", "swept");
    r["oracle_key"] = in.at(in.at(row, "", "oracle"), "oracle", "key");
    const nlohmann::json& gl = in.at(row, "", "gl");
    r["gl"] = gl;
    // Who measured the times: the GL renderer, or for an image the renderer its cost file names.
    const std::string renderer =
        gl.is_object() ? gl.value("renderer", "") : result.value("renderer", std::string());
    if (!renderer.empty()) t.renderers.insert(renderer);
    t.results.push_back(std::move(r));
}

nlohmann::json failedJson(const std::vector<SweepFailure>& failed) {
    nlohmann::json j = nlohmann::json::array();
    for (const SweepFailure& f : failed)
        j.push_back({{"task", f.task},
                     {"scene", f.scene},
                     {"label", f.label},
                     {"reason", f.reason},
                     {"log", f.log}});
    return j;
}

}  // namespace

SweepMerge mergeSweep(const fs::path& dir, bool imagesChecked) {
    const SweepPlan plan = readPlan(dir);
    SweepMerge out;
    Rows rows = readRows(dir, plan, imagesChecked, out.warnings);
    const std::vector<std::string> swept = sweptColumns(plan);
    Tables t;
    t.csv << "scene,light,technique,label,metric,value,task";
    for (const std::string& name : swept) t.csv << ",param." << csvField(name);
    t.csv << "\n";
    try {
        for (const auto& [index, row] : rows.done)
            addRow(t, plan, swept, index, row,
                   JsonReader(sweepRowPath(dir, plan.tasks[index]).string()));
    } catch (const nlohmann::json::exception& e) {
        throwInputError((dir / "rows").string(), "",
                        std::string("a row is malformed: ") + e.what());
    }
    writeFileAtomically(dir / "metrics.csv", t.csv.str());
    writeFileAtomically(dir / "metrics_wide.csv", t.wide.text());
    const nlohmann::json metrics = {{"schema_version", kMetricsSchemaVersion},
                                    {"sweep_format", kSweepFormat},
                                    {"tool", toolJson()},
                                    {"sweep", {{"name", plan.name}, {"spec_file", plan.specFile}}},
                                    {"tasks", plan.tasks.size()},
                                    {"finished", rows.done.size()},
                                    {"failed", failedJson(rows.failed)},
                                    {"results", t.results}};
    writeFileAtomically(dir / "metrics.json", metrics.dump(1) + "\n");

    SweepReportInput& report = t.report;
    report.specFile = plan.specFile.string();
    report.sweepName = plan.name;
    report.tasks = plan.tasks.size();
    report.failed = rows.failed;
    for (const std::string& r : t.renderers)
        report.timedOn += (report.timedOn.empty() ? "" : "; ") + r;
    report.provenance = {{"tool", toolVersionString()},
                         {"spec", plan.specFile.string()},
                         {"spec hash", plan.specHash},
                         {"tasks", std::to_string(plan.tasks.size())}};
    writeSweepReport((dir / "report.html").string(), report);

    out.name = plan.name;
    out.tasks = plan.tasks.size();
    out.finished = rows.done.size();
    out.failed = std::move(rows.failed);
    out.metricsCsv = dir / "metrics.csv";
    out.metricsWideCsv = dir / "metrics_wide.csv";
    out.metricsJson = dir / "metrics.json";
    out.report = dir / "report.html";
    return out;
}

}  // namespace so
