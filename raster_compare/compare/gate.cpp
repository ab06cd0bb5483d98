#include "raster_compare/compare/gate.h"

#include <cstdint>
#include <filesystem>
#include <map>

#include "core/error.h"
#include "core/json_reader.h"
#include "raster_compare/compare/baseline.h"
#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/metrics.h"

namespace so {

using nlohmann::json;

bool globMatch(const std::string& p, const std::string& t) {
    size_t pi = 0, ti = 0, star = std::string::npos, mark = 0;
    while (ti < t.size()) {
        if (pi < p.size() && (p[pi] == '?' || p[pi] == t[ti])) {
            ++pi, ++ti;
        } else if (pi < p.size() && p[pi] == '*') {
            star = pi++;
            mark = ti;
        } else if (star != std::string::npos) {
            pi = star + 1;
            ti = ++mark;
        } else {
            return false;
        }
    }
    while (pi < p.size() && p[pi] == '*') ++pi;
    return pi == p.size();
}

namespace {

std::map<std::string, json> flatMap(const json& row) {
    std::map<std::string, json> out;
    for (auto& [name, value] : flatMetrics(row)) out[name] = std::move(value);
    return out;
}

struct Rule {
    std::string scene = "*", light = "*", technique = "*";
    std::map<std::string, double> max;
};

// metrics.json is user input too (CI gates a file from an earlier job), so its shape is checked
// before it is read: a broken file is an InputError naming the field, never a json::type_error or
// a read of a missing key through const operator[] (undefined behaviour).
bool nestedDeeperThan(const json& j, int depth) {
    if (!j.is_structured()) return false;
    if (depth == 0) return true;
    for (const json& v : j)
        if (nestedDeeperThan(v, depth - 1)) return true;
    return false;
}

}  // namespace

void checkMetricsShape(const json& metrics, const std::string& mp) {
    const JsonReader r(mp);
    const json* version = JsonReader::find(metrics, "schema_version");
    if (!version || !version->is_number_integer() || version->get<int64_t>() < 1 ||
        version->get<int64_t>() > kMaxMetricsSchema || !metrics.contains("results"))
        throwInputError(
            mp, "schema_version",
            "not a metrics.json of schema_version 1 to " + std::to_string(kMaxMetricsSchema));
    if (const json* scene = JsonReader::find(metrics, "scene")) {
        r.requireObject(*scene, "scene");
        if (const json* file = JsonReader::find(*scene, "file")) r.string(*file, "scene.file");
    }
    const json& results = metrics["results"];
    r.requireArray(results, "results");
    for (size_t i = 0; i < results.size(); ++i) {
        const std::string f = JsonReader::index("results", i);
        r.requireObject(results[i], f);
        for (const char* key : {"technique", "label"})
            if (const json* v = JsonReader::find(results[i], key)) r.string(*v, f + "." + key);
        const json& lights = r.at(results[i], f, "lights");
        r.requireObject(lights, f + ".lights");
        for (const auto& [light, m] : lights.items()) {
            const std::string lf = f + ".lights." + printable(light, 40);
            r.requireObject(m, lf);
            // Metrics nest two levels (docs/metrics.md); the bound keeps flatMetrics' recursion
            // shallow.
            if (nestedDeeperThan(m, 8)) r.fail(lf, "nested too deeply");
        }
    }
}

namespace {

// A limit's metric must be in the table (metric_table.h), so a misspelled limit is an error, not
// a pass. A name the table has but this run lacks (the temporal metrics without a camera path, a
// metric newer than an old file's schema_version) is not applicable there: one limits file serves
// every run.
void checkMetricName(const std::string& name, const std::string& lf, const std::string& field) {
    if (findMetric(name)) return;
    std::string hint;
    for (const std::string& n : nearestMetrics(name)) hint += (hint.empty() ? "" : ", ") + n;
    throwInputError(lf, field,
                    "unknown metric (" + (hint.empty() ? "" : "did you mean " + hint + "? ") +
                        "see docs/metrics.md or `shadow-oracle metrics`)");
}

std::map<std::string, double> readMax(const json& j, const std::string& lf,
                                      const std::string& field) {
    const JsonReader r(lf);
    std::map<std::string, double> out;
    r.requireObject(j, field);
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string f = field + "." + printable(it.key(), 60);
        checkMetricName(it.key(), lf, f);
        out[it.key()] = r.number(*it, f);
    }
    return out;
}

Rule readRule(const json& r, const std::string& lf, size_t i) {
    const JsonReader reader(lf);
    const std::string f = JsonReader::index("rules", i);
    reader.checkKeys(r, f, {"scene", "light", "technique", "max"});
    Rule rule;
    for (auto [key, pattern] : {std::pair{"scene", &rule.scene}, std::pair{"light", &rule.light},
                                std::pair{"technique", &rule.technique}})
        if (const json* v = JsonReader::find(r, key)) *pattern = reader.string(*v, f + "." + key);
    rule.max = readMax(reader.at(r, f, "max"), lf, f + ".max");
    return rule;
}

std::vector<Rule> readRules(const json& limits, const std::string& lf) {
    const JsonReader r(lf);
    r.checkKeys(limits, "", {"limits_format", "default", "rules", "baseline"});
    // Format 2 added `baseline` (docs/gate.md#baseline); format 1 files are read as they were.
    const double format = r.number(r.at(limits, "", "limits_format"), "limits_format");
    if (format != 1.0 && format != 2.0)
        r.fail("limits_format", "unsupported version " + JsonReader::numberText(format) +
                                    " (this tool reads 1 and 2)");
    if (limits.contains("baseline")) {
        if (format != 2.0) r.fail("baseline", "needs limits_format 2");
        readBaselineSettings(&limits, lf);  // checked here too: a typo fails without --baseline
    }
    std::vector<Rule> rules;
    if (limits.contains("default"))
        rules.push_back({"*", "*", "*", readMax(limits["default"], lf, "default")});
    if (limits.contains("rules")) {
        r.requireArray(limits["rules"], "rules");
        for (size_t i = 0; i < limits["rules"].size(); ++i)
            rules.push_back(readRule(limits["rules"][i], lf, i));
    }
    return rules;
}

}  // namespace

std::vector<GateCheck> evaluateGate(const json& metrics, const std::string& metricsPath,
                                    const json& limits, const std::string& limitsPath) {
    // Version 2 added metrics and made aliasing_rate null on area lights; version 3 added metrics
    // and turned penumbra_bias's sign, version 4 added cost.oracle_ms_at_equal_error
    // (docs/metrics.md); version 5 added rows of external images (compare --image), whose costs
    // may be null: the gate reads all five.
    checkMetricsShape(metrics, metricsPath);
    const std::vector<Rule> rules = readRules(limits, limitsPath);
    const auto sceneObject = metrics.find("scene");
    const std::string scene =
        sceneObject == metrics.end() ? std::string() : sceneObject->value("file", "");
    const std::string sceneName = std::filesystem::path(scene).filename().string();
    std::vector<GateCheck> checks;
    for (const auto& r : metrics["results"]) {
        const std::string technique = r.value("technique", ""), label = r.value("label", technique);
        for (const auto& [light, m] : r["lights"].items()) {
            std::map<std::string, json> flat = flatMap(m);
            // Later rules override earlier ones for the same metric.
            std::map<std::string, double> applicable;
            for (const Rule& rule : rules) {
                const bool sceneOk =
                    globMatch(rule.scene, scene) || globMatch(rule.scene, sceneName);
                const bool techOk =
                    globMatch(rule.technique, technique) || globMatch(rule.technique, label);
                if (sceneOk && globMatch(rule.light, light) && techOk)
                    for (const auto& [k, v] : rule.max) applicable[k] = v;
            }
            for (const auto& [metric, maximum] : applicable) {
                const json& v = flat[metric];
                checks.push_back({sceneName, light, label, metric, maximum,
                                  v.is_number() ? std::optional(v.get<double>()) : std::nullopt});
            }
        }
    }
    return checks;
}

}  // namespace so
