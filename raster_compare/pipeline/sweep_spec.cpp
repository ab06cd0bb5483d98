#include "raster_compare/pipeline/sweep_spec.h"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <system_error>

#include "core/error.h"
#include "core/hash.h"
#include "core/read_file.h"
#include "raster_compare/pipeline/sweep_grid.h"
#include "raster_compare/pipeline/sweep_images.h"
#include "raster_compare/pipeline/sweep_settings.h"
#include "raster_compare/pipeline/sweep_spec_json.h"

// The reading of a spec is split by what it reads: sweep_spec_json.h (its values), sweep_settings.h
// (what every task shares), sweep_grid.h (the techniques' parameter grids), sweep_images.h (the
// "images" entries); the plan's folder is sweep_plan_file.cpp's.
namespace so {

namespace fs = std::filesystem;
using namespace sweep_detail;

namespace {

// One entry of "scenes": a path or a glob, relative to the spec's folder.
std::vector<fs::path> matchScenes(const std::string& pattern, const fs::path& specDir,
                                  const std::string& file, const std::string& field) {
    const fs::path p = fs::path(pattern).is_absolute() ? fs::path(pattern) : specDir / pattern;
    std::vector<fs::path> found;
    std::error_code ec;  // a name too long for the file system is "no such file", not an exception
    if (pattern.find_first_of("*?[") == std::string::npos) {
        if (!fs::is_regular_file(p, ec))
            throwInputError(file, field, "no such scene file: " + printable(p.string()));
        return {p};
    }
    glob_t g{};
    const int rc = ::glob(p.c_str(), 0, nullptr, &g);
    for (size_t i = 0; rc == 0 && i < g.gl_pathc; ++i)
        if (fs::is_regular_file(g.gl_pathv[i], ec)) found.emplace_back(g.gl_pathv[i]);
    ::globfree(&g);
    if (found.empty()) throwInputError(file, field, "matches no scene file: " + printable(pattern));
    std::sort(found.begin(), found.end());
    return found;
}

std::vector<SweepScene> expandScenes(const Json& spec, const fs::path& specDir,
                                     const std::string& file) {
    if (!spec.contains("scenes") || !spec["scenes"].is_array() || spec["scenes"].empty())
        throwInputError(file, "scenes", "must be a non-empty list of scene paths or globs");
    std::vector<SweepScene> scenes;
    std::set<fs::path> seen;
    for (size_t i = 0; i < spec["scenes"].size(); ++i) {
        const std::string field = "scenes[" + std::to_string(i) + "]";
        for (const fs::path& p :
             matchScenes(string(spec["scenes"][i], file, field), specDir, file, field)) {
            const fs::path abs = fs::weakly_canonical(p);
            if (!seen.insert(abs).second) continue;  // a scene two globs match runs once
            // Named as written: relative to the spec's folder ("../contact_box.scene.json") when
            // the entry is, so that names and ids do not depend on where the checkout lies.
            const fs::path rel = abs.lexically_relative(fs::weakly_canonical(specDir));
            const bool relative = !fs::path(spec["scenes"][i].get<std::string>()).is_absolute();
            scenes.push_back({relative && !rel.empty() ? rel.generic_string() : abs.string(), abs});
        }
    }
    return scenes;
}

void expandTasks(const std::string& file, SweepPlan& plan, const SettingValidator& validate) {
    const Json& spec = plan.spec;
    const bool hasImages = spec.contains("images");
    if (hasImages && (!spec["images"].is_array() || spec["images"].empty()))
        throwInputError(file, "images",
                        "must be a non-empty list of {\"name\", \"path\", \"params\"}");
    if (spec.contains("techniques") || !hasImages)
        if (!spec.contains("techniques") || !spec["techniques"].is_array() ||
            spec["techniques"].empty())
            throwInputError(file, "techniques",
                            "must be a non-empty list of {\"name\", \"params\"} (or give "
                            "\"images\")");
    std::vector<SweepTask> settings;
    if (spec.contains("techniques"))
        for (size_t ti = 0; ti < spec["techniques"].size(); ++ti)
            expandTechnique(spec["techniques"][ti], ti, file, validate, settings);
    if (settings.size() * plan.scenes.size() > kMaxSweepTasks)
        throwInputError(file, "techniques",
                        "more than " + std::to_string(kMaxSweepTasks) + " tasks in all");
    std::vector<SweepTask> images;
    if (hasImages)
        for (size_t ii = 0; ii < spec["images"].size(); ++ii)
            expandImages(spec["images"][ii], ii, plan, file, validate,
                         settings.size() * plan.scenes.size(), images);
    std::set<std::string> ids;
    const auto add = [&](SweepTask task, const char* field) {
        task.id = hashBytes(plan.scenes[task.scene].name + "\n" + task.label).substr(0, 12);
        if (!ids.insert(task.id).second)
            throwInputError(file, field,
                            "the setting " + task.label + " is listed twice for scene " +
                                plan.scenes[task.scene].name);
        plan.tasks.push_back(std::move(task));
    };
    for (size_t si = 0; si < plan.scenes.size(); ++si) {
        for (const SweepTask& s : settings) {
            SweepTask task = s;
            task.scene = si;
            add(std::move(task), "techniques");
        }
        for (const SweepTask& image : images)
            if (image.scene == si) add(image, "images");
    }
}

}  // namespace

std::string shortestNumber(double v) {
    char text[32];
    // Whole numbers as such: resolution=1000, not the equally short 1e+03.
    if (v == std::floor(v) && std::fabs(v) < 1e15) {
        std::snprintf(text, sizeof text, "%.0f", v);
        return text;
    }
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, v);
        if (std::strtod(text, nullptr) == v) break;
    }
    return text;
}

SweepPlan planSweep(const fs::path& specPath, const SettingValidator& validate) {
    return planSweepText(readFileCapped(specPath, specPath.string(), kMaxSpecBytes), specPath,
                         validate);
}

SweepPlan planSweepText(const std::string& text, const fs::path& specPath,
                        const SettingValidator& validate) {
    const std::string file = specPath.string();
    if (text.size() > kMaxSpecBytes) throwInputError(file, "", "sweep spec too large");
    SweepPlan plan;
    try {
        plan.spec = Json::parse(text);
    } catch (const Json::exception& e) {  // parse_error, or out_of_range for a number like 1e400
        throwInputError(file, "", "invalid JSON: " + printable(e.what(), 160));
    }
    checkKeys(plan.spec, topLevelKeys(), file, "");
    if (!plan.spec.contains("sweep_format"))
        throwInputError(file, "sweep_format", "missing (this tool writes and reads 1)");
    if (integer(plan.spec["sweep_format"], file, "sweep_format", 0, 1 << 30) != kSweepFormat)
        throwInputError(file, "sweep_format", "unsupported (this tool reads 1; docs/sweep.md)");
    plan.specFile = fs::absolute(specPath);
    plan.specHash = hashBytes(text);
    plan.name = plan.specFile.stem().string();
    if (plan.spec.contains("name")) {
        plan.name = string(plan.spec["name"], file, "name");
    }
    plan.settings = parseSettings(plan.spec, file);
    plan.scenes = expandScenes(plan.spec, plan.specFile.parent_path(), file);
    expandTasks(file, plan, validate);
    plan.taskCount = plan.tasks.size();
    return plan;
}

}  // namespace so
