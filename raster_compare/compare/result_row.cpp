#include "raster_compare/compare/result_row.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/json_reader.h"

namespace so {

using nlohmann::json;

std::string ParamValue::text() const {
    if (kind == Kind::Name) return name;
    char text[32];
    // Whole numbers as such: resolution=1000, not the equally short 1e+03.
    if (number == std::floor(number) && std::fabs(number) < 1e15) {
        std::snprintf(text, sizeof text, "%.0f", number);
        return text;
    }
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, number);
        if (std::strtod(text, nullptr) == number) break;
    }
    return text;
}

ParamValue paramValueOfJson(const json& j) {
    using K = ParamValue::Kind;
    if (j.is_number_integer()) return {K::Integer, j.get<double>(), ""};
    if (j.is_number()) return {K::Number, j.get<double>(), ""};
    return {K::Name, 0.0, j.is_string() ? j.get<std::string>() : j.dump()};
}

std::optional<double> LightRow::value(const MetricInfo& m) const {
    const auto it = values_.find(&m);
    return it == values_.end() ? std::nullopt : it->second;
}

std::optional<double> LightRow::value(const std::string& name) const {
    return value(metricInfo(name));
}

const LightRow* ResultRow::light(const std::string& name) const {
    for (const LightRow& l : lights)
        if (l.light == name) return &l;
    return nullptr;
}

namespace {

// The metric's JSON value in `metrics` by its dotted name, or null where it is absent: where a
// group on the way is null or absent (penumbra_width_error_px on a hard light, cost.work of an
// image), its members are absent. A group that is not an object is bad input.
const json* metricJson(const json& metrics, const std::string& name, const JsonReader& r,
                       std::string& field) {
    const json* at = &metrics;
    size_t from = 0;
    for (size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', from)) {
        const std::string group = name.substr(from, dot - from);
        field += "." + group;
        const json* v = JsonReader::find(*at, group);
        if (!v || v->is_null()) return nullptr;
        r.requireObject(*v, field);
        at = v;
        from = dot + 1;
    }
    const std::string leaf = name.substr(from);
    field += "." + leaf;
    return JsonReader::find(*at, leaf);
}

std::string optionalString(const json& object, const std::string& key, const JsonReader& r,
                           const std::string& field) {
    const json* v = JsonReader::find(object, key);
    if (!v || v->is_null()) return "";
    return r.string(*v, field + "." + key);
}

}  // namespace

LightRow readLightRow(const json& metrics, const std::string& light, const JsonReader& r,
                      const std::string& field) {
    r.requireObject(metrics, field);
    LightRow row;
    row.light = light;
    for (const MetricInfo& m : allMetrics()) {
        std::string f = field;
        const json* v = metricJson(metrics, m.name, r, f);
        if (!v) continue;
        if (v->is_boolean() && m.unit == MetricUnit::Flag) {
            row.set(m, v->get<bool>() ? 1.0 : 0.0);
            continue;
        }
        const double x = r.nullableNumber(*v, f);
        row.set(m, std::isnan(x) ? std::nullopt : std::optional(x));
    }
    return row;
}

// "provenance": {"fidelity", "parts": [{"of", "anchor", "fidelity", "deviations"?}]}, absent
// before issue 63 and for images.
void readProvenance(ResultRow& row, const json& result, const JsonReader& r,
                    const std::string& field) {
    const json* p = JsonReader::find(result, "provenance");
    if (!p || p->is_null()) return;
    const std::string f = field + ".provenance";
    r.requireObject(*p, f);
    row.fidelity = optionalString(*p, "fidelity", r, f);
    const json* parts = JsonReader::find(*p, "parts");
    if (!parts) return;
    if (!parts->is_array()) r.fail(f + ".parts", "not an array");
    for (size_t i = 0; i < parts->size(); ++i) {
        const json& part = (*parts)[i];
        const std::string pf = f + ".parts[" + std::to_string(i) + "]";
        r.requireObject(part, pf);
        row.provenanceText +=
            (row.provenanceText.empty() ? "" : "\n") + optionalString(part, "of", r, pf) + ": " +
            optionalString(part, "fidelity", r, pf) + ", " + optionalString(part, "anchor", r, pf);
        if (const json* d = JsonReader::find(part, "deviations"); d && d->is_array())
            for (const json& line : *d)
                if (line.is_string()) row.provenanceText += "\n  - " + line.get<std::string>();
    }
}

ResultRow readResultRow(const json& result, const JsonReader& r, const std::string& field) {
    r.requireObject(result, field);
    ResultRow row;
    row.technique = optionalString(result, "technique", r, field);
    row.family = optionalString(result, "family", r, field);
    // The label names the row everywhere; schema_version 1 files may name only the technique.
    row.label = optionalString(result, "label", r, field);
    if (row.label.empty()) row.label = row.technique;
    if (row.label.empty()) r.fail(field + ".label", "missing");
    if (const json* p = JsonReader::find(result, "parameters"); p && p->is_object())
        for (auto it = p->begin(); it != p->end(); ++it)
            row.parameters[it.key()] = paramValueOfJson(*it);
    readProvenance(row, result, r, field);
    if (const json* h = JsonReader::find(result, "history_frames"); h && !h->is_null())
        row.historyFrames = r.integer(*h, field + ".history_frames", 0, 1 << 20);
    const json& lights = r.at(result, field, "lights");
    r.requireObject(lights, field + ".lights");
    for (const auto& [light, m] : lights.items())
        row.lights.push_back(readLightRow(m, light, r, field + ".lights." + printable(light, 60)));
    return row;
}

}  // namespace so
