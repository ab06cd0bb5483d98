#include "raster_compare/compare/gate.h"

#include <cstdint>
#include <filesystem>
#include <map>

#include "core/error.h"
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
    const auto version = metrics.is_object() ? metrics.find("schema_version") : metrics.end();
    if (version == metrics.end() || !version->is_number_integer() || version->get<int64_t>() < 1 ||
        version->get<int64_t>() > kMaxMetricsSchema || !metrics.contains("results"))
        throwInputError(
            mp, "schema_version",
            "not a metrics.json of schema_version 1 to " + std::to_string(kMaxMetricsSchema));
    const auto scene = metrics.find("scene");
    if (scene != metrics.end()) {
        if (!scene->is_object()) throwInputError(mp, "scene", "expected an object");
        if (scene->contains("file") && !(*scene)["file"].is_string())
            throwInputError(mp, "scene.file", "expected a string");
    }
    const json& results = metrics["results"];
    if (!results.is_array()) throwInputError(mp, "results", "expected an array");
    for (size_t i = 0; i < results.size(); ++i) {
        const std::string f = "results[" + std::to_string(i) + "]";
        const json& r = results[i];
        if (!r.is_object()) throwInputError(mp, f, "expected an object");
        for (const char* key : {"technique", "label"})
            if (r.contains(key) && !r[key].is_string())
                throwInputError(mp, f + "." + key, "expected a string");
        if (!r.contains("lights") || !r["lights"].is_object())
            throwInputError(mp, f + ".lights", "missing or not an object");
        for (const auto& [light, m] : r["lights"].items()) {
            const std::string lf = f + ".lights." + printable(light, 40);
            if (!m.is_object()) throwInputError(mp, lf, "expected an object of metrics");
            // Metrics nest two levels (docs/metrics.md); the bound keeps flatMetrics' recursion
            // shallow.
            if (nestedDeeperThan(m, 8)) throwInputError(mp, lf, "nested too deeply");
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
    std::map<std::string, double> out;
    if (!j.is_object()) throwInputError(lf, field, "expected an object of metric: maximum");
    for (auto it = j.begin(); it != j.end(); ++it) {
        checkMetricName(it.key(), lf, field + "." + printable(it.key(), 60));
        if (!it->is_number()) throwInputError(lf, field + "." + it.key(), "expected a number");
        out[it.key()] = it->get<double>();
    }
    return out;
}

Rule readRule(const json& r, const std::string& lf, size_t i) {
    const std::string f = "rules[" + std::to_string(i) + "]";
    if (!r.is_object()) throwInputError(lf, f, "expected an object");
    for (auto it = r.begin(); it != r.end(); ++it) {
        if (it.key() == "max") continue;
        if (it.key() != "scene" && it.key() != "light" && it.key() != "technique")
            throwInputError(lf, f + "." + printable(it.key(), 40),
                            "unknown key (valid: scene, light, technique, max)");
        if (!it->is_string()) throwInputError(lf, f + "." + it.key(), "expected a pattern string");
    }
    Rule rule;
    rule.scene = r.value("scene", "*");
    rule.light = r.value("light", "*");
    rule.technique = r.value("technique", "*");
    if (!r.contains("max")) throwInputError(lf, f + ".max", "missing");
    rule.max = readMax(r["max"], lf, f + ".max");
    return rule;
}

std::vector<Rule> readRules(const json& limits, const std::string& lf) {
    if (!limits.is_object()) throwInputError(lf, "", "expected an object");
    for (auto it = limits.begin(); it != limits.end(); ++it)
        if (it.key() != "limits_format" && it.key() != "default" && it.key() != "rules" &&
            it.key() != "baseline")
            throwInputError(lf, printable(it.key(), 40),
                            "unknown key (valid: limits_format, default, rules, baseline)");
    // Format 2 added `baseline` (docs/gate.md#baseline); format 1 files are read as they were.
    const auto format = limits.find("limits_format");
    if (format == limits.end() || !format->is_number() ||
        (format->get<double>() != 1.0 && format->get<double>() != 2.0))
        throwInputError(lf, "limits_format", "missing or not 1 or 2");
    if (limits.contains("baseline")) {
        if (format->get<double>() != 2.0) throwInputError(lf, "baseline", "needs limits_format 2");
        readBaselineSettings(&limits, lf);  // checked here too: a typo fails without --baseline
    }
    std::vector<Rule> rules;
    if (limits.contains("default"))
        rules.push_back({"*", "*", "*", readMax(limits["default"], lf, "default")});
    if (limits.contains("rules")) {
        if (!limits["rules"].is_array()) throwInputError(lf, "rules", "expected an array");
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
