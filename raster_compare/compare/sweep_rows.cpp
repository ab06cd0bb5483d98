// The helpers the sweep report's sections share (sweep_sections.h).
#include <algorithm>
#include <cstdio>

#include "raster_compare/compare/artifacts.h"
#include "raster_compare/compare/html.h"
#include "raster_compare/compare/result_row.h"
#include "raster_compare/compare/sweep_sections.h"

namespace so::sweep {

std::string html(const std::string& s) {
    return htmlEscape(s);
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

std::string exact(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

const std::string kMae = "mae";
const std::string kAcne = artifactClass(Artifact::Acne).metric;
const std::string kPeterPanning = artifactClass(Artifact::PeterPanning).metric;

std::optional<double> metricOf(const SweepRow& r, const std::string& metric) {
    return r.light().value(metric);
}

std::string metricName(const std::string& metric) {
    const MetricInfo* info = findMetric(metric);
    return info ? metricLabel(*info) : metric;
}

std::string metricTitle(const std::string& metric) {
    const std::string name = metricName(metric);
    return "<b>" + html(name) + "</b>" +
           (name == metric ? "" : " <code>" + html(metric) + "</code>");
}

const std::vector<Cost>& costs() {
    static const std::vector<Cost> c = [] {
        std::vector<Cost> out;
        for (const MetricInfo* m : costAxes(false))
            out.push_back({m->name, metricLabel(*m), displayUnit(*m), displayScale(*m)});
        return out;
    }();
    return c;
}

std::vector<std::string> techniquesOf(const std::vector<const SweepRow*>& rows) {
    std::vector<std::string> names;
    for (const SweepRow* r : rows)
        if (std::find(names.begin(), names.end(), r->result.technique) == names.end())
            names.push_back(r->result.technique);
    return names;
}

std::vector<const SweepRow*> rowsOf(const Group& g, const std::string& technique) {
    std::vector<const SweepRow*> out;
    for (const SweepRow* r : g.rows)
        if (r->result.technique == technique) out.push_back(r);
    return out;
}

bool anyHas(const std::vector<const SweepRow*>& rows, const std::string& metric) {
    return std::any_of(rows.begin(), rows.end(),
                       [&](const SweepRow* r) { return metricOf(*r, metric).has_value(); });
}

bool anyNonZero(const std::vector<const SweepRow*>& rows, const std::string& metric) {
    return std::any_of(rows.begin(), rows.end(), [&](const SweepRow* r) {
        const std::optional<double> v = metricOf(*r, metric);
        return v && *v != 0.0;
    });
}

std::vector<std::string> errorMetrics(const std::vector<const SweepRow*>& rows) {
    std::vector<std::string> out;
    if (anyHas(rows, kMae)) out.push_back(kMae);
    for (const ArtifactClass& c : kArtifactClasses)
        if (anyHas(rows, c.metric)) out.push_back(c.metric);
    return out;
}

std::string shortLabel(const SweepRow& r) {
    const std::string prefix = r.result.technique + ":";
    const std::string& label = r.result.label;
    if (label.compare(0, prefix.size(), prefix) == 0) return label.substr(prefix.size());
    return label == r.result.technique ? "(defaults)" : label;
}

std::string sweptName(const SweepRow& r) {
    if (r.swept.empty()) return shortLabel(r);
    std::string s;
    for (const auto& [name, value] : r.swept)
        s += (s.empty() ? "" : ", ") + name + "=" + value.text();
    return s;
}

}  // namespace so::sweep
