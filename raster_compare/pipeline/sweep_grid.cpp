#include "raster_compare/pipeline/sweep_grid.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <utility>

#include "core/error.h"
#include "core/json_reader.h"

namespace so::sweep_detail {
namespace {

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

}  // namespace

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

}  // namespace so::sweep_detail
