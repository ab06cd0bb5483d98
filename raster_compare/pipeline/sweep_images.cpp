#include "raster_compare/pipeline/sweep_images.h"

#include <fnmatch.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <system_error>
#include <utility>

#include "core/error.h"
#include "core/hash.h"
#include "core/json_reader.h"
#include "core/read_file.h"
#include "raster_compare/pipeline/sweep_grid.h"

namespace so {

namespace fs = std::filesystem;

namespace sweep_detail {
namespace {

// A scene's name for an image path: its file name up to the first dot ("spot_objects").
std::string sceneStem(const SweepScene& scene) {
    const std::string name = scene.path.filename().string();
    return name.substr(0, name.find('.'));
}

// An "images" entry's path with {scene} and each {PARAM} replaced by the setting's values.
std::string imagePath(const std::string& pattern, const SweepScene& scene, const SweepTask& s,
                      const std::string& file, const std::string& field) {
    std::string out;
    for (size_t i = 0; i < pattern.size();) {
        if (pattern[i] == '}') throwInputError(file, field, "a '}' without its '{'");
        if (pattern[i] != '{') {
            out += pattern[i++];
            continue;
        }
        const size_t end = pattern.find('}', i);
        if (end == std::string::npos) throwInputError(file, field, "a '{' without its '}'");
        const std::string key = pattern.substr(i + 1, end - i - 1);
        std::string value;
        bool found = key == "scene";
        if (found) value = sceneStem(scene);
        for (const std::string& setting : s.settings)
            if (setting.compare(0, key.size() + 1, key + "=") == 0) {
                value = setting.substr(key.size() + 1);
                found = true;
            }
        if (!found)
            throwInputError(file, field,
                            "{" + printable(key, 40) + "} is neither {scene} nor a parameter");
        out += value;
        i = end + 1;
    }
    return out;
}

// The scenes an "images" entry covers: all, or those its "scenes" names or globs match (the
// names as in the plan, relative to the spec's folder).
std::vector<size_t> imageScenes(const Json& entry, const std::vector<SweepScene>& scenes,
                                const std::string& file, const std::string& field) {
    std::vector<size_t> covered;
    if (!entry.contains("scenes")) {
        for (size_t si = 0; si < scenes.size(); ++si) covered.push_back(si);
        return covered;
    }
    const Json& list = entry["scenes"];
    if (!list.is_array() || list.empty())
        throwInputError(file, field + ".scenes",
                        "must be a non-empty list of scene names or globs");
    for (size_t k = 0; k < list.size(); ++k) {
        const std::string f = field + ".scenes[" + std::to_string(k) + "]";
        const std::string pattern = string(list[k], file, f);
        bool matched = false;
        for (size_t si = 0; si < scenes.size(); ++si)
            if (::fnmatch(pattern.c_str(), scenes[si].name.c_str(), 0) == 0) {
                matched = true;
                if (std::find(covered.begin(), covered.end(), si) == covered.end())
                    covered.push_back(si);
            }
        if (!matched)
            throwInputError(file, f,
                            "matches none of the sweep's scenes: " + printable(pattern, 80));
    }
    std::sort(covered.begin(), covered.end());
    return covered;
}

// What a renderer's and its parameters' names may hold: no ':' ',' '=' of a label, no '{' of a
// path.
constexpr const char* kNameChars =
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.";

}  // namespace

void expandImages(const Json& entry, size_t ii, const SweepPlan& plan, const std::string& file,
                  const SettingValidator& validate, size_t before, std::vector<SweepTask>& tasks) {
    const std::string field = "images[" + std::to_string(ii) + "]";
    checkKeys(entry, {"name", "path", "params", "scenes", "encoding"}, file, field);
    if (!entry.contains("name") || !entry["name"].is_string())
        throwInputError(file, field + ".name", "must be the renderer's name");
    const std::string name = entry["name"].get<std::string>();
    if (name.empty() || name.size() > 64 || name.find_first_not_of(kNameChars) != std::string::npos)
        throwInputError(file, field + ".name", "must be 1 to 64 of A-Z a-z 0-9 _ - .");
    bool builtIn = true;
    try {
        validate(name, {});
    } catch (const InputError&) {
        builtIn = false;
    }
    if (builtIn)
        throwInputError(file, field + ".name",
                        "\"" + name + "\" is a built-in technique: name the renderer instead");
    if (!entry.contains("path") || !entry["path"].is_string() ||
        entry["path"].get<std::string>().empty())
        throwInputError(file, field + ".path", "must be the image's path (with {scene}, {PARAM})");
    std::string encoding = "linear";
    if (entry.contains("encoding")) {
        encoding = JsonReader(file).oneOf(plain(entry["encoding"]), field + ".encoding", "encoding",
                                          {"linear", "srgb"});
    }
    // A parameter's name goes into the label and the path: no separator of either.
    if (entry.contains("params") && entry["params"].is_object())
        for (const auto& [key, v] : entry["params"].items())
            if (key.empty() || key.size() > 64 ||
                key.find_first_not_of(kNameChars) != std::string::npos)
                throwInputError(file, field + ".params." + printable(key, 40),
                                "a parameter's name must be 1 to 64 of A-Z a-z 0-9 _ - .");
    const std::vector<SweepTask> grid =
        expandGrid(entry, name, file, field, before, /*namesAllowed=*/false);
    const fs::path specDir = plan.specFile.parent_path();
    for (size_t si : imageScenes(entry, plan.scenes, file, field))
        for (const SweepTask& s : grid) {
            if (before + tasks.size() >= kMaxSweepTasks)
                throwInputError(file, "images",
                                "more than " + std::to_string(kMaxSweepTasks) + " tasks in all");
            SweepTask task = s;
            task.scene = si;
            const fs::path p = imagePath(entry["path"].get<std::string>(), plan.scenes[si], s, file,
                                         field + ".path");
            task.image = (p.is_absolute() ? p : specDir / p).lexically_normal().string();
            task.encoding = encoding;
            std::error_code ec;
            if (!fs::is_regular_file(task.image, ec))
                throwInputError(file, field + ".path",
                                "no such image for " + task.label + " on " + plan.scenes[si].name +
                                    ": " + printable(task.image));
            tasks.push_back(std::move(task));
        }
}

}  // namespace sweep_detail

std::string imageInputsHash(const fs::path& image) {
    // Images are bounded by the compare's reader; this cap only keeps a wrong path (a disk image)
    // from being hashed whole.
    constexpr uint64_t kMaxImageBytes = uint64_t(4) << 30;
    std::string bytes = readFileCapped(image, image.string(), kMaxImageBytes);
    const fs::path cost = image.string() + ".json";
    std::error_code ec;
    if (fs::is_regular_file(cost, ec))
        bytes += "\ncost\n" + readFileCapped(cost, cost.string(), kMaxImageBytes);
    return hashBytes(bytes);
}

bool imageRowIsStale(const nlohmann::json& row, const SweepTask& task) {
    if (task.image.empty()) return false;
    // What the row says first, so that a malformed row costs no read of the image.
    if (!row.is_object() || !row.contains("task") || !row["task"].is_object()) return true;
    const nlohmann::json& t = row["task"];
    if (!t.contains("image") || !t["image"].is_object()) return true;
    const nlohmann::json hash = t["image"].contains("hash") ? t["image"]["hash"] : nlohmann::json();
    if (!hash.is_string()) return true;
    try {
        return hash.get<std::string>() != imageInputsHash(task.image);
    } catch (const InputError&) {
        return true;  // gone or unreadable: the task runs again and says why
    }
}

}  // namespace so
