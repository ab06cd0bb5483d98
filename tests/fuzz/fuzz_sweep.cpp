// Fuzzes the sweep spec reader (raster_compare/pipeline/sweep_spec.cpp, planSweepText): the spec a
// user writes for `shadow-oracle sweep` (docs/sweep.md). The input is the spec's text; the spec is
// named SCRATCH/spec/spec.json (never written: only its folder is used, to resolve the scenes), and
// that folder holds a few empty scene files (a.scene.json, b.scene.json, sub/c.scene.json, and
// ../outside.scene.json beside it), since scenes are only matched and checked to exist, not loaded,
// and a few empty images for "images" entries (img/a_1.exr, a_2, b_1, b_2, c_1.png).
// The technique table is a small stand-in for the tool's (which needs GL), with the same rules as
// raster_compare/gl/params.cpp: unknown technique or key, a value that is not a finite number, not
// an integer or out of range is an InputError. Beyond "only InputError", the harness checks what
// the plan promises (see checkPlan) and aborts on a violation.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "raster_compare/pipeline/sweep_spec.h"
#include "tests/fuzz/fuzz_common.h"
#include "tests/fuzz/fuzz_json_input.h"

namespace {

namespace fs = std::filesystem;

struct Param {
    const char* name;
    double min, max;
    bool integer;
    std::vector<std::string> names = {};  // a method parameter's: value k is names[k]
};
struct Technique {
    const char* name;
    std::vector<Param> params;
};

const std::vector<Technique>& techniques() {
    static const std::vector<Technique> table = {
        {"basic", {{"resolution", 256, 8192, true}}},
        {"slope-bias",
         {{"alpha", 0, 16, false}, {"min", 0, 16, false}, {"resolution", 256, 8192, true}}},
        {"pcf",
         {{"kernel", 1, 15, true},
          {"resolution", 256, 8192, true},
          {"pattern", 0, 1, true, {"grid", "poisson"}}}},
    };
    return table;
}

[[noreturn]] void finding(const std::string& what) {
    std::fprintf(stderr, "so-fuzz: FINDING: %s\n", what.c_str());
    std::abort();
}

// The stand-in for createTechnique: the same checks as parseParams (raster_compare/gl/params.cpp).
so::ParamNumbers validate(const std::string& name, const std::vector<std::string>& settings) {
    const Technique* t = nullptr;
    for (const Technique& c : techniques())
        if (name == c.name) t = &c;
    if (!t) so::throwInputError("technique", so::printable(name, 40), "unknown technique");
    const std::string file = "technique " + name;
    so::ParamNumbers numbers;
    for (const std::string& setting : settings) {
        const size_t eq = setting.find('=');
        if (eq == std::string::npos || eq == 0)
            so::throwInputError(file, so::printable(setting, 40), "expected key=value");
        const std::string key = setting.substr(0, eq), text = setting.substr(eq + 1);
        const Param* p = nullptr;
        for (const Param& c : t->params)
            if (key == c.name) p = &c;
        if (!p) so::throwInputError(file, so::printable(key, 40), "unknown parameter");
        const auto named = std::find(p->names.begin(), p->names.end(), text);
        if (named != p->names.end()) {
            numbers[key] = double(named - p->names.begin());
            continue;
        }
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v))
            so::throwInputError(file, key, "\"" + so::printable(text, 40) + "\" is not a number");
        if (p->integer && v != std::floor(v)) so::throwInputError(file, key, "must be an integer");
        if (!(v >= p->min && v <= p->max)) so::throwInputError(file, key, "out of range");
        numbers[key] = v;
    }
    return numbers;
}

// The spec's folder, made once per process: empty scene files for the globs and paths to find.
const fs::path& specDir() {
    static const fs::path dir = [] {
        const fs::path d = so::fuzz::scratchDir() / "spec";
        for (const char* f : {"spec/a.scene.json", "spec/b.scene.json", "spec/sub/c.scene.json",
                              "outside.scene.json", "spec/img/a_1.exr", "spec/img/a_2.exr",
                              "spec/img/b_1.exr", "spec/img/b_2.exr", "spec/img/c_1.png"})
            so::fuzz::writeFile(so::fuzz::scratchDir() / f, "");
        return d;
    }();
    return dir;
}

// A glob that leaves the scratch folder (absolute, or through "..") could walk the whole file
// system: the user's own choice in the tool, a timeout here. Such inputs are not run; plain paths
// out of the folder are (they are only checked to exist).
bool globsStayInside(const nlohmann::json& spec) {
    if (!spec.is_object() || !spec.contains("scenes") || !spec["scenes"].is_array()) return true;
    for (const nlohmann::json& s : spec["scenes"]) {
        if (!s.is_string()) continue;
        const std::string p = s.get<std::string>();
        if (p.find_first_of("*?[") == std::string::npos) continue;
        if (fs::path(p).is_absolute() || p.find("..") != std::string::npos) return false;
    }
    return true;
}

// How many values the spec gives `key` in some entry of `list` ("techniques" or "images") named
// `name` (the largest).
size_t valuesInSpec(const nlohmann::ordered_json& spec, const char* list, const std::string& name,
                    const std::string& key) {
    size_t most = 0;
    for (const auto& t : spec.at(list)) {
        if (t.at("name").get<std::string>() != name || !t.contains("params")) continue;
        const auto& params = t.at("params");
        if (!params.contains(key)) continue;
        const auto& v = params.at(key);
        size_t n = 1;
        if (v.is_array()) n = v.size();
        if (v.is_object()) n = size_t(v.at("steps").get<double>());
        most = std::max(most, n);
    }
    return most;
}

bool isId(const std::string& id) {
    if (id.size() != 12) return false;
    for (char c : id)
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
    return true;
}

// A task's image: an absolute path to a file, read as linear or srgb; none for a technique.
void checkImage(const so::SweepTask& t) {
    if (t.image.empty()) {
        if (!t.encoding.empty()) finding("task " + t.id + ": an encoding without an image");
        return;
    }
    if (!fs::path(t.image).is_absolute() || !fs::is_regular_file(t.image))
        finding("task " + t.id +
                ": image not an absolute path to a file: " + so::printable(t.image));
    if (t.encoding != "linear" && t.encoding != "srgb")
        finding("task " + t.id + ": encoding " + so::printable(t.encoding));
}

// What the plan promises (raster_compare/pipeline/sweep_spec.h), checked cheaply: a plan can have
// 10^6 tasks. Per scene, in scene order: the same technique settings, then that scene's images.
void checkPlan(const so::SweepPlan& plan) {
    if (plan.tasks.size() > so::kMaxSweepTasks) finding("more tasks than kMaxSweepTasks");
    if (plan.scenes.empty() || plan.tasks.empty()) finding("a plan without scenes or tasks");
    std::set<std::string> sceneNames;
    for (const so::SweepScene& s : plan.scenes) {
        if (!sceneNames.insert(s.name).second) finding("scene listed twice: " + s.name);
        if (!s.path.is_absolute() || !fs::is_regular_file(s.path))
            finding("scene path not an absolute path to a file: " + s.path.string());
    }
    std::unordered_set<std::string_view> ids;
    std::map<std::pair<std::string, std::string>, size_t> valuesOf;  // (entry name, key): count
    std::vector<size_t> techniqueTasks(plan.scenes.size(), 0);
    for (size_t i = 0; i < plan.tasks.size(); ++i) {
        const so::SweepTask& t = plan.tasks[i];
        if (!isId(t.id)) finding("task id is not 12 hex digits: " + so::printable(t.id));
        if (!ids.insert(t.id).second) finding("task id twice: " + t.id);
        if (t.scene >= plan.scenes.size()) finding("task " + t.id + ": scene index out of range");
        if (i > 0 && (t.scene < plan.tasks[i - 1].scene ||
                      (t.scene == plan.tasks[i - 1].scene && t.image.empty() &&
                       !plan.tasks[i - 1].image.empty())))
            finding("task " + t.id + ": not in scene order, techniques before images");
        checkImage(t);
        if (t.image.empty()) ++techniqueTasks[t.scene];
        std::string label = t.technique;
        for (size_t k = 0; k < t.settings.size(); ++k) label += (k ? "," : ":") + t.settings[k];
        if (t.label != label || t.label.rfind(t.technique, 0) != 0)
            finding("task " + t.id + ": label " + so::printable(t.label) + " is not its settings");
        // A technique's settings as the stand-in reads them: a method's name as its number.
        const so::ParamNumbers numbers =
            t.image.empty() ? validate(t.technique, t.settings) : so::ParamNumbers{};
        for (const auto& [key, v] : t.swept) {
            if (!std::isfinite(v)) finding("task " + t.id + ": swept value not finite");
            bool inSettings = false;
            for (const std::string& s : t.settings)
                if (s.size() > key.size() && s[key.size()] == '=' && s.rfind(key, 0) == 0)
                    inSettings =
                        (t.image.empty() ? numbers.at(key)
                                         : std::strtod(s.c_str() + key.size() + 1, nullptr)) == v;
            if (!inSettings) finding("task " + t.id + ": swept " + key + " not in its settings");
            // The spec is valid here: every lookup in valuesInSpec finds what it looks for.
            const char* list = t.image.empty() ? "techniques" : "images";
            auto [it, added] =
                valuesOf.try_emplace({std::string(list) + " " + t.technique, key}, 0);
            if (added) it->second = valuesInSpec(plan.spec, list, t.technique, key);
            if (it->second < 2) finding("task " + t.id + ": " + key + " swept but given one value");
        }
    }
    for (size_t n : techniqueTasks)
        if (n != techniqueTasks[0]) finding("the scenes do not all have the same settings");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    if (auto j = so::fuzz::parseJson(text); j && !globsStayInside(*j)) return 0;
    const fs::path spec = specDir() / "spec.json";
    so::fuzz::expectOnlyInputErrors([&] { checkPlan(so::planSweepText(text, spec, validate)); });
    return 0;
}
