#include "raster_compare/gate_command.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

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

json readJson(const std::string& path, const std::string& what) {
    std::ifstream in(path);
    if (!in) throwInputError(path, "", "cannot be read (" + what + ")");
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throwInputError(path, "", "invalid JSON: " + printable(e.what(), 160));
    }
}

void flatten(const json& j, const std::string& prefix, std::map<std::string, json>& out) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string name = prefix.empty() ? it.key() : prefix + "." + it.key();
        if (it->is_object())
            flatten(*it, name, out);
        else
            out[name] = *it;
    }
}

std::string xmlEscape(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
            case '&':
                o += "&amp;";
                break;
            case '<':
                o += "&lt;";
                break;
            case '>':
                o += "&gt;";
                break;
            case '"':
                o += "&quot;";
                break;
            default:
                o += c;
        }
    }
    return o;
}

struct Rule {
    std::string scene = "*", light = "*", technique = "*";
    std::map<std::string, double> max;
};

}  // namespace

int runGateCommand(const GateOptions& options) {
    const json metrics = readJson(options.metricsPath, "metrics");
    const json limits = readJson(options.limitsPath, "limits");
    const std::string& lf = options.limitsPath;
    if (!metrics.is_object() || metrics.value("schema_version", 0) != 1 ||
        !metrics.contains("results"))
        throwInputError(options.metricsPath, "schema_version",
                        "not a metrics.json of schema_version 1");
    if (!limits.is_object()) throwInputError(lf, "", "expected an object");
    for (auto it = limits.begin(); it != limits.end(); ++it)
        if (it.key() != "limits_format" && it.key() != "default" && it.key() != "rules")
            throwInputError(lf, printable(it.key(), 40),
                            "unknown key (valid: limits_format, default, rules)");
    if (limits.value("limits_format", 0) != 1)
        throwInputError(lf, "limits_format", "missing or not 1");

    // Every metric name the metrics file can have, so a misspelled limit is an error, not a pass.
    std::set<std::string> known;
    for (const auto& r : metrics["results"])
        for (const auto& [light, m] : r["lights"].items()) {
            std::map<std::string, json> flat;
            flatten(m, "", flat);
            for (const auto& [k, v] : flat) known.insert(k);
        }
    auto readMax = [&](const json& j, const std::string& field) {
        std::map<std::string, double> out;
        if (!j.is_object()) throwInputError(lf, field, "expected an object of metric: maximum");
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (!known.count(it.key()))
                throwInputError(lf, field + "." + printable(it.key(), 60),
                                "unknown metric (see docs/metrics.md)");
            if (!it->is_number()) throwInputError(lf, field + "." + it.key(), "expected a number");
            out[it.key()] = it->get<double>();
        }
        return out;
    };
    std::vector<Rule> rules;
    if (limits.contains("default"))
        rules.push_back({"*", "*", "*", readMax(limits["default"], "default")});
    if (limits.contains("rules")) {
        if (!limits["rules"].is_array()) throwInputError(lf, "rules", "expected an array");
        for (size_t i = 0; i < limits["rules"].size(); ++i) {
            const json& r = limits["rules"][i];
            const std::string f = "rules[" + std::to_string(i) + "]";
            if (!r.is_object()) throwInputError(lf, f, "expected an object");
            Rule rule;
            for (auto it = r.begin(); it != r.end(); ++it) {
                if (it.key() == "max") continue;
                if (it.key() != "scene" && it.key() != "light" && it.key() != "technique")
                    throwInputError(lf, f + "." + printable(it.key(), 40),
                                    "unknown key (valid: scene, light, technique, max)");
                if (!it->is_string())
                    throwInputError(lf, f + "." + it.key(), "expected a pattern string");
            }
            rule.scene = r.value("scene", "*");
            rule.light = r.value("light", "*");
            rule.technique = r.value("technique", "*");
            if (!r.contains("max")) throwInputError(lf, f + ".max", "missing");
            rule.max = readMax(r["max"], f + ".max");
            rules.push_back(rule);
        }
    }

    const std::string scene = metrics["scene"].value("file", "");
    const std::string sceneName = std::filesystem::path(scene).filename().string();
    struct Check {
        std::string cls, name, failure;
    };
    std::vector<Check> checks;
    size_t failures = 0;
    for (const auto& r : metrics["results"]) {
        const std::string technique = r.value("technique", ""), label = r.value("label", technique);
        for (const auto& [light, m] : r["lights"].items()) {
            std::map<std::string, json> flat;
            flatten(m, "", flat);
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
                Check c{sceneName + "." + light, label + " " + metric, ""};
                const json& v = flat[metric];
                if (v.is_number() && v.get<double>() > maximum) {
                    std::ostringstream os;
                    os << "FAIL " << sceneName << " " << light << " " << label << " " << metric
                       << " = " << v.get<double>() << " > " << maximum;
                    c.failure = os.str();
                    std::cout << c.failure << "\n";
                    ++failures;
                }
                checks.push_back(c);
            }
        }
    }
    std::cout << checks.size() - failures << " passed, " << failures << " failed\n";
    if (!options.junitPath.empty()) {
        std::ofstream x(options.junitPath);
        if (!x) throwInputError(options.junitPath, "--junit", "cannot be written");
        x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n  <testsuite "
             "name=\"shadow-oracle gate\" tests=\""
          << checks.size() << "\" failures=\"" << failures << "\">\n";
        for (const Check& c : checks) {
            x << "    <testcase classname=\"" << xmlEscape(c.cls) << "\" name=\""
              << xmlEscape(c.name) << "\"";
            if (c.failure.empty())
                x << "/>\n";
            else
                x << ">\n      <failure message=\"" << xmlEscape(c.failure)
                  << "\"/>\n    </testcase>\n";
        }
        x << "  </testsuite>\n</testsuites>\n";
    }
    return failures ? 1 : 0;
}

}  // namespace so
