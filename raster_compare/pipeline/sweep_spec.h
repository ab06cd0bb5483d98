// A sweep (docs/sweep.md): the spec a user writes (scenes, oracle options, techniques with
// parameter grids), expanded once into a plan of tasks (scene x technique setting) with stable ids,
// kept as DIR/sweep.json so that every later step (a local job, a Slurm array task, the merge)
// reads the same list, whatever the globs would match by then. A spec is read by sweep_spec.cpp
// with its internal parts (sweep_spec_json, sweep_settings, sweep_grid, sweep_images); the plan's
// folder is sweep_plan_file.cpp's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/option_table.h"
#include "core/trace_option_table.h"

namespace so {

inline constexpr int kSweepFormat = 1;
// At most this many tasks in one sweep: a bound on what a mistyped range can allocate.
inline constexpr size_t kMaxSweepTasks = 100000;

struct SweepScene {
    std::string name;            // as matched, relative to the spec's folder
    std::filesystem::path path;  // absolute
};

struct SweepTask {
    std::string id;  // stable: a hash of the scene's name and the label
    size_t scene = 0;
    std::string technique;
    std::string label;                  // "slope-bias:alpha=2,min=0.5", what compare takes
    std::vector<std::string> settings;  // "key=value"
    // The parameters given more than one value for this technique, with this task's values.
    std::vector<std::pair<std::string, double>> swept;
    // An "images" task (a renderer's render of this setting, judged as compare --image judges
    // it): the image's absolute path and "linear" or "srgb" for a PNG; empty for a technique.
    std::string image;
    std::string encoding;
};

// The oracle options a spec sets (docs/sweep.md, "oracle"); what it leaves out keeps compare's
// default. Width and height are the raster's too.
struct SweepOracleSettings {
    int width = 0, height = 0;  // 0: the scene camera's
    // The "oracle" block's trace options by key (core/trace_option_table.h), checked; the ones
    // left out keep compare's defaults.
    TraceOptionValues values;
};

// What every task of the sweep shares.
struct SweepSettings {
    SweepOracleSettings oracle;
    // The top-level keys of the raster and comparison option tables (core/raster_option_table.h,
    // core/compare_option_table.h), checked; the ones left out keep compare's defaults.
    OptionValues raster, compare;
    bool keepOutputs = false;  // keep each task's compare folder (images, error EXRs)
};

struct SweepPlan {
    std::string name;
    std::filesystem::path specFile;  // absolute
    std::string specHash;            // of the spec file's bytes
    nlohmann::ordered_json spec;     // as written
    SweepSettings settings;
    std::vector<SweepScene> scenes;
    std::vector<SweepTask> tasks;
    size_t taskCount = 0;  // read back: tasks.size() once read
};

// Reads, validates (every setting is created, so every error names its field) and expands a spec:
// per scene, the technique settings, then the images of that scene (each of which must exist).
// Creates a setting of a technique, throwing InputError when the technique or a setting is not
// valid, and returns every parameter's value (a method's name as its number): createTechnique
// (raster_compare/gl/technique.h) in the tool; the fuzz harness, which links no GL, passes its own.
using ParamNumbers = std::map<std::string, double>;
using SettingValidator = std::function<ParamNumbers(const std::string& technique,
                                                    const std::vector<std::string>& settings)>;
SweepPlan planSweep(const std::filesystem::path& specPath, const SettingValidator& validate);
// The same from the spec's text; `specPath` names it in errors and anchors relative scene paths.
SweepPlan planSweepText(const std::string& text, const std::filesystem::path& specPath,
                        const SettingValidator& validate);

// DIR/sweep.json and DIR/tasks.jsonl: writes them (atomically), or reads them back; a missing or
// foreign file is an InputError naming it.
void writePlan(const std::filesystem::path& dir, const SweepPlan& plan);
// The tasks' settings are not validated again: each task's compare does. Without `withTasks`,
// `tasks` stays empty (taskCount says how many): what one task needs, with readPlanTask.
SweepPlan readPlan(const std::filesystem::path& dir, bool withTasks = true);
SweepTask readPlanTask(const std::filesystem::path& dir, const SweepPlan& plan, size_t index);

// Files of a sweep folder, in one place (docs/sweep.md, "The output folder").
std::filesystem::path sweepRowPath(const std::filesystem::path& dir, const SweepTask& task);
std::filesystem::path sweepTaskLogPath(const std::filesystem::path& dir, size_t index);
std::filesystem::path sweepOracleLogPath(const std::filesystem::path& dir, size_t scene);
std::filesystem::path sweepOracleCacheDir(const std::filesystem::path& dir);
// DIR/scene_hashes.json: per scene (by index), the content hash its rows were made from.
std::filesystem::path sweepSceneHashesPath(const std::filesystem::path& dir);

// The tasks without a row, by plan index, and the scenes they need, both ascending: what a run
// (local or --slurm) has left to do.
struct UnfinishedTasks {
    std::vector<size_t> tasks, scenes;
};
UnfinishedTasks unfinishedTasks(const std::filesystem::path& dir, const SweepPlan& plan);

// Writes `text` to a temporary file beside `path` and renames it over `path`: readers see the old
// file or the whole new one, never a part.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

// The shortest text that reads back as the same double ("0.1", "2048").
std::string shortestNumber(double v);

// What an image task's row records of its inputs: the hash of the image's bytes and of its cost
// file's (PATH.json, when present), so that a re-rendered image makes its row stale.
std::string imageInputsHash(const std::filesystem::path& image);
// Whether an image task's row (any JSON: a malformed one counts as stale) was made from other bytes
// of its image or cost file than are there now, or its image is gone; false for a technique's task.
bool imageRowIsStale(const nlohmann::json& row, const SweepTask& task);

}  // namespace so
