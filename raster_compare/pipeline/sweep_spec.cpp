#include "raster_compare/pipeline/sweep_spec.h"

#include <fnmatch.h>
#include <glob.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "core/compare_option_table.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/json_reader.h"
#include "core/raster_option_table.h"
#include "core/read_file.h"
#include "core/trace_option_table.h"

namespace so {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// A spec is small; anything larger is not one (and must not be read whole).
constexpr uintmax_t kMaxSpecBytes = 4u << 20;
constexpr size_t kMaxValuesPerParam = 100000;

// The spec is an ordered_json (its settings keep the file's order); its values are checked by
// the one reader of user JSON (core/json_reader.h), so its errors read like every other file's.
nlohmann::json plain(const Json& v) {
    return nlohmann::json(v);
}

void checkKeys(const Json& obj, const std::set<std::string>& allowed, const std::string& file,
               const std::string& field) {
    const JsonReader r(file);
    if (!obj.is_object()) r.requireObject(plain(obj), field);
    const std::vector<std::string> valid(allowed.begin(), allowed.end());
    for (const auto& [key, value] : obj.items()) r.checkKey(key, field, valid);
}

double number(const Json& v, const std::string& file, const std::string& field) {
    return JsonReader(file).number(plain(v), field);
}

int integer(const Json& v, const std::string& file, const std::string& field, int lo, int hi) {
    return JsonReader(file).integer(plain(v), field, lo, hi);
}

bool boolean(const Json& v, const std::string& file, const std::string& field) {
    return JsonReader(file).boolean(plain(v), field);
}

std::string string(const Json& v, const std::string& file, const std::string& field) {
    return JsonReader(file).string(plain(v), field);
}

// One option of the spec (core/option_table.h), checked by its table's row.
OptionValue optionValue(const OptionSpec& spec, const Json& v, const std::string& file,
                        const std::string& field) {
    OptionValue out;
    if (spec.type == OptionType::Name) {
        out.text = string(v, file, field);
    } else if (spec.type == OptionType::Flag) {
        out.number = boolean(v, file, field) ? 1.0 : 0.0;
    } else {
        out.number = number(v, file, field);
    }
    checkOption(spec, out, file, field, /*allowUnsetZero=*/false);
    return out;
}

// The image size lies at the spec's top level; the other trace options in its "oracle" block.
bool topLevelTraceOption(const std::string& key) {
    return key == "width" || key == "height";
}

// The spec's top-level keys: its own, the image size and the tables' sweep rows.
std::set<std::string> topLevelKeys() {
    std::set<std::string> keys = {"sweep_format", "name",   "scenes",     "width", "height",
                                  "keep_outputs", "oracle", "techniques", "images"};
    for (const OptionTable* table : {&rasterOptionTable(), &compareOptionTable()})
        for (const OptionSpec& spec : table->rows)
            if (spec.surfaces & kSurfaceSweep) keys.insert(spec.key);
    return keys;
}

// The spec's oracle block: the trace options the table offers to sweeps, with their ranges.
void parseOracle(const Json& o, const std::string& file, SweepOracleSettings& oracle) {
    std::set<std::string> keys;
    for (const TraceOptionSpec& spec : traceOptionTable())
        if ((spec.surfaces & kSurfaceSweep) && !topLevelTraceOption(spec.key))
            keys.insert(spec.key);
    checkKeys(o, keys, file, "oracle");
    for (const auto& [key, value] : o.items())
        oracle.values[key] = optionValue(traceOption(key), value, file, "oracle." + key);
}

SweepSettings parseSettings(const Json& spec, const std::string& file) {
    SweepSettings s;
    if (spec.contains("width"))
        s.oracle.width =
            int(optionValue(traceOption("width"), spec["width"], file, "width").number);
    if (spec.contains("height"))
        s.oracle.height =
            int(optionValue(traceOption("height"), spec["height"], file, "height").number);
    for (const auto& [table, values] :
         {std::pair{&rasterOptionTable(), &s.raster}, std::pair{&compareOptionTable(), &s.compare}})
        for (const OptionSpec& row : table->rows)
            if ((row.surfaces & kSurfaceSweep) && spec.contains(row.key))
                (*values)[row.key] = optionValue(row, spec[row.key], file, row.key);
    if (spec.contains("keep_outputs"))
        s.keepOutputs = boolean(spec["keep_outputs"], file, "keep_outputs");
    if (spec.contains("oracle")) parseOracle(spec["oracle"], file, s.oracle);
    return s;
}

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

// A parameter's values: a number, a list of numbers, or {"from", "to", "steps"[, "log"]}.
std::vector<double> paramValues(const Json& v, const std::string& file, const std::string& field) {
    if (v.is_number()) return {number(v, file, field)};
    std::vector<double> values;
    if (v.is_array()) {
        if (v.empty() || v.size() > kMaxValuesPerParam)
            throwInputError(file, field, "a list needs 1 to 100000 numbers");
        for (size_t i = 0; i < v.size(); ++i)
            values.push_back(number(v[i], file, field + "[" + std::to_string(i) + "]"));
        return values;
    }
    if (!v.is_object())
        throwInputError(file, field, "must be a number, a list or {\"from\", \"to\", \"steps\"}");
    checkKeys(v, {"from", "to", "steps", "log"}, file, field);
    for (const char* k : {"from", "to", "steps"})
        if (!v.contains(k)) throwInputError(file, field + "." + k, "missing");
    const double from = number(v["from"], file, field + ".from");
    const double to = number(v["to"], file, field + ".to");
    const int steps = integer(v["steps"], file, field + ".steps", 1, int(kMaxValuesPerParam));
    const bool log = v.contains("log") && boolean(v["log"], file, field + ".log");
    if (log && (from <= 0 || to <= 0))
        throwInputError(file, field, "a log range needs from > 0 and to > 0");
    if (steps == 1) return {from};
    for (int i = 0; i < steps; ++i) {
        const double t = double(i) / double(steps - 1);
        // (1 - t) from + t to: finite for any finite ends, where from + (to - from) t overflows.
        double x = log ? from * std::pow(to / from, t) : (1.0 - t) * from + t * to;
        // To 12 significant digits, so that a step lands on the number the user means: 0.3, not
        // 0.1 + 0.2 = 0.30000000000000004; 10 of 0.001..1000 in log steps, not 9.99999999999999.
        char text[32];
        std::snprintf(text, sizeof text, "%.12g", x);
        x = i == steps - 1 ? to : std::strtod(text, nullptr);
        if (!std::isfinite(x)) throwInputError(file, field, "a value of the range is not finite");
        values.push_back(x);
    }
    return values;
}

struct ParamGrid {
    std::string name;
    std::vector<double> values;         // NaN for a method's name, until the validator reads it
    std::vector<std::string> settings;  // "name=value" per value, formatted once
};

// A technique's method parameter by name ("pattern": "poisson" or ["spiral", "rotated"]): the
// names as given, the validator checks them against the technique's table. Null for numbers.
std::optional<std::vector<std::string>> methodNames(const Json& v, const std::string& file,
                                                    const std::string& field) {
    const bool names = v.is_string() || (v.is_array() && !v.empty() && v[0].is_string());
    if (!names) return std::nullopt;
    if (v.is_string()) return std::vector<std::string>{v.get<std::string>()};
    if (v.size() > kMaxValuesPerParam)
        throwInputError(file, field, "a list needs 1 to 100000 values");
    std::vector<std::string> out;
    for (size_t i = 0; i < v.size(); ++i) {
        const std::string at = field + "[" + std::to_string(i) + "]";
        if (!v[i].is_string()) throwInputError(file, at, "a list of names holds names only");
        const std::string name = v[i].get<std::string>();
        if (name.empty() || name.size() > 64 ||
            name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
            throwInputError(file, at, "a method's name is 1 to 64 of a-z 0-9 _ -");
        out.push_back(name);
    }
    return out;
}

std::string settingLabel(const std::string& technique, const std::vector<std::string>& settings) {
    std::string label = technique;
    for (size_t i = 0; i < settings.size(); ++i) label += (i ? "," : ":") + settings[i];
    return label;
}

// The settings of one grid ("params" of a "techniques" or "images" entry), the last parameter
// varying fastest; `before`: the settings of the entries before this one, for the bound.
std::vector<SweepTask> expandGrid(const Json& entry, const std::string& name,
                                  const std::string& file, const std::string& field, size_t before,
                                  bool namesAllowed) {
    std::vector<ParamGrid> grid;
    size_t count = 1;
    if (entry.contains("params")) {
        if (!entry["params"].is_object())
            JsonReader(file).requireObject(plain(entry["params"]), field + ".params");
        // Bounded as each parameter is read, so that no spec makes many large ranges first.
        for (const auto& [key, v] : entry["params"].items()) {
            const std::string at = field + ".params." + printable(key, 40);
            const auto names = namesAllowed ? methodNames(v, file, at) : std::nullopt;
            ParamGrid g{key, {}, {}};
            if (names) {
                g.values.assign(names->size(), std::numeric_limits<double>::quiet_NaN());
                for (const std::string& n : *names) g.settings.push_back(key + "=" + n);
            } else {
                g.values = paramValues(v, file, at);
                for (double x : g.values) g.settings.push_back(key + "=" + shortestNumber(x));
            }
            grid.push_back(std::move(g));
            count *= grid.back().values.size();
            if (count + before > kMaxSweepTasks)
                throwInputError(
                    file, field + ".params",
                    "the sweep has more than " + std::to_string(kMaxSweepTasks) + " settings");
        }
    }
    std::vector<SweepTask> settings;
    for (size_t k = 0; k < count; ++k) {
        SweepTask s;
        s.technique = name;
        size_t rest = k;
        for (size_t gi = grid.size(); gi-- > 0;) {
            const ParamGrid& g = grid[gi];
            const size_t vi = rest % g.values.size();
            rest /= g.values.size();
            s.settings.insert(s.settings.begin(), g.settings[vi]);
            if (g.values.size() > 1) s.swept.insert(s.swept.begin(), {g.name, g.values[vi]});
        }
        s.label = settingLabel(name, s.settings);
        settings.push_back(std::move(s));
    }
    return settings;
}

// The settings of one "techniques" entry, each created (so validated) before any work.
void expandTechnique(const Json& t, size_t ti, const std::string& file,
                     const SettingValidator& validate, std::vector<SweepTask>& settings) {
    const std::string field = "techniques[" + std::to_string(ti) + "]";
    checkKeys(t, {"name", "params"}, file, field);
    if (!t.contains("name") || !t["name"].is_string())
        throwInputError(file, field + ".name", "must be a technique name");
    const std::string name = t["name"].get<std::string>();
    try {
        validate(name, {});
    } catch (const InputError& e) {
        throwInputError(file, field + ".name", e.message());
    }
    for (SweepTask& s : expandGrid(t, name, file, field, settings.size(), /*namesAllowed=*/true)) {
        ParamNumbers numbers;
        try {
            numbers = validate(name, s.settings);  // every error before any work, with its field
        } catch (const InputError& e) {
            throwInputError(file, field + ".params", s.label + ": " + e.message());
        }
        // A method's name swept is its number in the rows, as metrics.json's parameters hold it.
        for (auto& [key, value] : s.swept)
            if (std::isnan(value)) value = numbers.at(key);
        settings.push_back(std::move(s));
    }
}

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

// The settings of one "images" entry, per scene it covers, each image present.
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

namespace {

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
