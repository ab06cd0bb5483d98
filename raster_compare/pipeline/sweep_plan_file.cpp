// A sweep's plan in its folder (docs/sweep.md, "The output folder"): DIR/sweep.json and
// DIR/tasks.jsonl written atomically and read back, and the paths of the folder's other files.
// Declared in sweep_spec.h.
#include <unistd.h>

#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/read_file.h"
#include "raster_compare/pipeline/sweep_settings.h"
#include "raster_compare/pipeline/sweep_spec.h"
#include "raster_compare/pipeline/sweep_spec_json.h"

namespace so {

namespace fs = std::filesystem;
using namespace sweep_detail;

namespace {

Json taskJson(const SweepTask& t) {
    Json swept = Json::object();
    for (const auto& [k, v] : t.swept) swept[k] = v;
    Json j = {{"id", t.id},       {"scene", t.scene},       {"technique", t.technique},
              {"label", t.label}, {"settings", t.settings}, {"swept", swept}};
    if (!t.image.empty()) {
        j["image"] = t.image;
        j["encoding"] = t.encoding;
    }
    return j;
}

SweepTask taskFromJson(const Json& j) {
    SweepTask t;
    t.id = j.at("id").get<std::string>();
    t.scene = j.at("scene").get<size_t>();
    t.technique = j.at("technique").get<std::string>();
    t.label = j.at("label").get<std::string>();
    t.settings = j.at("settings").get<std::vector<std::string>>();
    for (const auto& [k, v] : j.at("swept").items()) t.swept.emplace_back(k, v.get<double>());
    if (j.contains("image")) {
        t.image = j.at("image").get<std::string>();
        t.encoding = j.at("encoding").get<std::string>();
        if (t.encoding != "linear" && t.encoding != "srgb")
            throw Json::other_error::create(501, "unknown image encoding", &j);
    }
    return t;
}

// One line of tasks.jsonl as a task, checked against the plan.
SweepTask parseTaskLine(const std::string& line, const SweepPlan& plan, const std::string& file,
                        size_t index) {
    SweepTask t;
    try {
        t = taskFromJson(Json::parse(line));
    } catch (const Json::exception& e) {
        throwInputError(file, "line " + std::to_string(index + 1),
                        std::string("not a task: ") + e.what());
    }
    if (t.scene >= plan.scenes.size())
        throwInputError(file, "line " + std::to_string(index + 1), "scene index out of range");
    return t;
}

}  // namespace

fs::path sweepRowPath(const fs::path& dir, const SweepTask& task) {
    return dir / "rows" / (task.id + ".json");
}
UnfinishedTasks unfinishedTasks(const fs::path& dir, const SweepPlan& plan) {
    UnfinishedTasks left;
    std::set<size_t> scenes;
    for (size_t i = 0; i < plan.tasks.size(); ++i)
        if (!fs::exists(sweepRowPath(dir, plan.tasks[i]))) {
            left.tasks.push_back(i);
            scenes.insert(plan.tasks[i].scene);
        }
    left.scenes.assign(scenes.begin(), scenes.end());
    return left;
}
fs::path sweepTaskLogPath(const fs::path& dir, size_t index) {
    return dir / "logs" / ("task-" + std::to_string(index) + ".log");
}
fs::path sweepOracleLogPath(const fs::path& dir, size_t scene) {
    return dir / "logs" / ("oracle-" + std::to_string(scene) + ".log");
}
fs::path sweepOracleCacheDir(const fs::path& dir) {
    return dir / "oracles";
}
fs::path sweepSceneHashesPath(const fs::path& dir) {
    return dir / "scene_hashes.json";
}

void writeFileAtomically(const fs::path& path, const std::string& text) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    // Unique per process: two writers of one file (a task run twice) do not share a temp file.
    const fs::path tmp =
        path.parent_path() / ("." + path.filename().string() + ".tmp" + std::to_string(::getpid()));
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.flush();
        if (!out) throwInputError(tmp.string(), "", "cannot be written");
    }
    fs::rename(tmp, path, ec);
    if (ec) throwInputError(path.string(), "", "cannot be renamed into place: " + ec.message());
}

// The tasks go to tasks.jsonl, one per line, so that a task (an array task of thousands) reads its
// own line, not a plan of megabytes; sweep.json has the rest and is written last.
void writePlan(const fs::path& dir, const SweepPlan& plan) {
    std::string lines;
    for (const SweepTask& t : plan.tasks) lines += taskJson(t).dump() + "\n";
    writeFileAtomically(dir / "tasks.jsonl", lines);
    Json scenes = Json::array();
    for (const SweepScene& s : plan.scenes)
        scenes.push_back({{"name", s.name}, {"path", s.path.string()}});
    const Json j = {{"sweep_format", kSweepFormat},
                    {"name", plan.name},
                    {"spec_file", plan.specFile.string()},
                    {"spec_hash", plan.specHash},
                    {"spec", plan.spec},
                    {"scenes", scenes},
                    {"tasks", plan.tasks.size()},
                    {"tasks_file", "tasks.jsonl"}};
    writeFileAtomically(dir / "sweep.json", j.dump(1) + "\n");
}

SweepPlan readPlan(const fs::path& dir, bool withTasks) {
    const fs::path path = dir / "sweep.json";
    const std::string file = path.string();
    if (!fs::exists(path))
        throwInputError(file, "", "missing: not a sweep folder (made by `shadow-oracle sweep`)");
    Json j;
    try {
        j = Json::parse(readFileCapped(path, file, kMaxSpecBytes * 4));
    } catch (const Json::exception& e) {
        throwInputError(file, "", "invalid JSON: " + printable(e.what(), 160));
    }
    const JsonReader r(file);
    const nlohmann::json top = plain(j);
    if (r.integer(r.at(top, "", "sweep_format"), "sweep_format", 0, 1 << 30) != kSweepFormat)
        r.fail("sweep_format", "unsupported (this tool reads 1)");
    SweepPlan plan;
    plan.name = r.string(r.at(top, "", "name"), "name");
    plan.specFile = r.string(r.at(top, "", "spec_file"), "spec_file");
    plan.specHash = r.string(r.at(top, "", "spec_hash"), "spec_hash");
    r.at(top, "", "spec");
    plan.spec = j["spec"];  // the file's order, which the settings keep
    plan.settings = parseSettings(plan.spec, file);
    const nlohmann::json& scenes = r.at(top, "", "scenes");
    r.requireArray(scenes, "scenes");
    for (size_t i = 0; i < scenes.size(); ++i) {
        const std::string f = JsonReader::index("scenes", i);
        plan.scenes.push_back({r.string(r.at(scenes[i], f, "name"), f + ".name"),
                               r.string(r.at(scenes[i], f, "path"), f + ".path")});
    }
    plan.taskCount = r.count(r.at(top, "", "tasks"), "tasks");
    if (plan.taskCount > kMaxSweepTasks)
        r.outOfRange("tasks", "<= " + std::to_string(kMaxSweepTasks), double(plan.taskCount));
    if (!withTasks) return plan;
    const fs::path tasksPath = dir / "tasks.jsonl";
    std::istringstream in(readFileCapped(tasksPath, tasksPath.string(), uint64_t(1) << 32));
    std::string line;
    while (plan.tasks.size() < plan.taskCount && std::getline(in, line))
        plan.tasks.push_back(parseTaskLine(line, plan, tasksPath.string(), plan.tasks.size()));
    if (plan.tasks.size() != plan.taskCount)
        throwInputError(tasksPath.string(), "", "fewer tasks than sweep.json says");
    return plan;
}

SweepTask readPlanTask(const fs::path& dir, const SweepPlan& plan, size_t index) {
    const fs::path path = dir / "tasks.jsonl";
    const std::string text = readFileCapped(path, path.string(), uint64_t(1) << 32);
    size_t at = 0;
    for (size_t k = 0; k < index && at != std::string::npos; ++k) {
        at = text.find('\n', at);
        if (at != std::string::npos) ++at;
    }
    if (at == std::string::npos || at >= text.size())
        throwInputError(path.string(), "", "has no task " + std::to_string(index));
    const size_t end = text.find('\n', at);
    return parseTaskLine(text.substr(at, end == std::string::npos ? std::string::npos : end - at),
                         plan, path.string(), index);
}

}  // namespace so
