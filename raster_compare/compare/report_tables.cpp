// Compare's report: the tables of metrics and the chart of error against cost with its budget
// tables (report_sections.h), all read from the techniques' typed rows.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "raster_compare/compare/contact_pairs.h"
#include "raster_compare/compare/html.h"
#include "raster_compare/compare/report_sections.h"
#include "raster_compare/compare/result_row.h"
#include "raster_compare/compare/tradeoff.h"

namespace so::report_parts {

namespace {

// A numeric column of the tables, in the report's order: its metric, whose header, meaning,
// number format and which way is better are the metric table's (metric_table.h), so the report
// and docs/metrics.md say the same; whether the summary shows it (the all-metrics table shows
// every column) and whether it is an error the chart can plot.
struct Column {
    const MetricInfo* metric;
    bool inSummary;
    bool charted;
};

// The report's columns in its order. After memory come the metric table's work axes, in its order
// (a new one is shown without a line here), fragments and bytes moved in the summary.
const std::vector<Column>& columns() {
    static const std::vector<Column> cols = [] {
        std::vector<Column> out;
        const auto add = [&](const char* name, bool inSummary, bool charted) {
            out.push_back({&metricInfo(name), inSummary, charted});
        };
        add("mae", true, true);
        add("acne_rate", true, true);
        add("penumbra_spread_rate", true, false);
        add("peter_panning_rate", true, true);
        add("boundary_displacement_px.p95", true, true);
        add("aliasing_rate", false, false);
        add("light_bleeding_rate", true, true);
        add("penumbra_mae", true, true);
        add("penumbra_bias", true, false);
        add("penumbra_width_error_px.mean", true, false);
        add("temporal_flicker_rate", true, true);
        add("sequence.mae_mean", true, false);
        add("sequence.flicker_rate", true, false);
        add("sequence.lag_mae", true, false);
        add("sequence.ghosting_rate", true, false);
        add("false_shadow_rate", false, false);
        add("false_lit_rate", false, false);
        add("cost.frame_ms", true, false);
        add("cost.shadow_map_ms", true, false);
        add("cost.visibility_ms", true, false);
        add("cost.camera_ms", true, false);
        add("cost.memory_bytes", true, false);
        for (const MetricInfo* m : costAxes(true))
            if (m->costAxis == CostAxis::Work)
                out.push_back({m,
                               m == &metricInfo("cost.work.fragments") ||
                                   m == &metricInfo("cost.work.bytes_moved"),
                               false});
        add("cost.oracle_ms_at_equal_error", false, false);
        return out;
    }();
    return cols;
}

// Whether some technique has a value of the metric for the light.
bool anyValue(const ReportInput& in, size_t li, const MetricInfo& m) {
    return std::any_of(in.techniques.begin(), in.techniques.end(), [&](const ReportTechnique& t) {
        return lightRow(t, in, li).value(m).has_value();
    });
}

// "frame time (ms)", "acne": the label, and the unit its values are shown in (a count's is not
// said).
std::string titleWithUnit(const MetricInfo& m) {
    const std::string unit = m.unit == MetricUnit::Count ? "" : displayUnit(m);
    return metricLabel(m) + (unit.empty() ? "" : " (" + unit + ")");
}

// The header cell of a numeric column: sortable, with its direction and meaning as a tooltip (a
// signed column's tip says itself that nearer zero is better).
std::string headerCell(const MetricInfo& m) {
    const std::string direction = m.better == Better::Lower    ? "; lower is better"
                                  : m.better == Better::Higher ? "; higher is better"
                                                               : "";
    return "<th data-col=\"" + html(m.name) + "\" title=\"" + html(m.name) + ": " +
           html(m.description) + direction + " (docs/metrics.md)\">" + html(titleWithUnit(m)) +
           "</th>";
}

// The cells of one column over rows, the best (least, or nearest zero) marked; none in a column
// whose metric has no better direction (the oracle's time at equal error).
std::vector<std::string> columnCells(const MetricInfo& m,
                                     const std::vector<const LightRow*>& rows) {
    std::optional<double> best;
    auto score = [&](double v) {
        return m.better == Better::SmallerMagnitude ? std::fabs(v)
               : m.better == Better::Higher         ? -v
                                                    : v;
    };
    for (const LightRow* l : rows)
        if (const auto v = l->value(m); v && (!best || score(*v) < *best)) best = score(*v);
    std::vector<std::string> cells;
    for (const LightRow* l : rows) {
        const std::optional<double> v = l->value(m);
        char data[40] = "";
        if (v) std::snprintf(data, sizeof data, "%.9g", *v);
        const bool isBest = v && rows.size() > 1 && m.better != Better::None && score(*v) == *best;
        cells.push_back(std::string("<td data-v=\"") + data + "\"" +
                        (isBest ? " class=\"best\"" : "") + ">" +
                        (v ? formatMetricValue(m, *v) : "–") + "</td>");
    }
    return cells;
}

// The error and cost a chart can plot: those with a value for some technique of the light, as
// (key, name, metric); a cost's key is its name without "cost.".
struct ChartChoice {
    std::string key, name;
    const MetricInfo* metric;
};

// The errors: penumbra_mae first (the chart opens on it on area lights), then the charted columns;
// the costs: the metric table's cost axes.
std::vector<ChartChoice> chartChoices(const ReportInput& in, size_t li, bool costs) {
    std::vector<const MetricInfo*> metrics;
    if (costs) {
        metrics = costAxes(true);
    } else {
        metrics.push_back(&metricInfo("penumbra_mae"));
        for (const Column& c : columns())
            if (c.charted && c.metric != metrics.front()) metrics.push_back(c.metric);
    }
    std::vector<ChartChoice> out;
    const std::string prefix = "cost.";
    for (const MetricInfo* m : metrics) {
        std::string key = m->name;
        if (costs && key.rfind(prefix, 0) == 0) key = key.substr(prefix.size());
        if (anyValue(in, li, *m)) out.push_back({key, titleWithUnit(*m), m});
    }
    return out;
}

// One light's techniques as points of error against one cost (docs/metrics.md, "Error against
// cost"): penumbra_mae on area lights (the oracle's curve beside them, against frame time), mae
// on hard ones.
struct ChartData {
    std::vector<TradeoffPoint> points;
    std::vector<std::pair<double, double>> oracle;  // (ms, penumbra mean stated half-width)
    std::optional<OracleExactPoint> exact;          // where the exact pass gave V
    std::string error;                              // the error's name, for the axis
    ChartChoice cost;
};

ChartData chartData(const ReportInput& in, size_t light, const ChartChoice& cost) {
    ChartData d;
    d.cost = cost;
    const bool area = hasPenumbra(in, light);
    d.error = area ? "penumbra_mae" : "mae";
    for (const ReportTechnique& t : in.techniques) {
        const LightRow& row = lightRow(t, in, light);
        const std::optional<double> error = row.value(area ? "penumbra_mae" : "mae");
        if (!error) continue;
        // An external image without that cost (or a technique without a time) has no point.
        const std::optional<double> c = row.value(*cost.metric);
        if (!c) continue;
        d.points.push_back(
            {t.row.label, t.curve, t.quality, *c * displayScale(*cost.metric), *error});
    }
    // The oracle's times are times: beside frame times only.
    if (!area || cost.key != "frame_ms") return d;
    if (light < in.oracleCurves.size())
        for (const auto& [ms, e] : in.oracleCurves[light])
            if (ms > 0.0 && e > 0.0) d.oracle.emplace_back(ms, e);
    if (light < in.oracleExact.size()) d.exact = in.oracleExact[light];
    return d;
}

// The chart read off at error budgets for one cost: the cheapest setting within each, and (area
// lights, against frame time) the oracle's time to state intervals that small. The script shows
// the table of the cost selected (data-cost); without it the first, frame time, shows.
std::string budgetTable(const ChartData& d, bool shown) {
    if (d.points.empty()) return "";
    const MetricInfo& cost = *d.cost.metric;
    static const std::vector<double> budgets = {0.2, 0.1, 0.05, 0.02, 0.01, 0.005};
    const std::vector<std::optional<size_t>> cheapest = cheapestAtBudgets(d.points, budgets);
    std::ostringstream s;
    s << "<div class=\"budget-box\" data-cost=\"" << html(d.cost.key) << "\""
      << (shown ? "" : " hidden") << "><p class=\"caption\">Read off at error budgets ("
      << html(d.error) << " against " << html(d.cost.name)
      << "):</p><table class=\"budget\"><tr><th>" << html(d.error)
      << " at most</th><th>cheapest setting</th><th>its cost</th>"
      << (d.oracle.empty() ? "" : "<th>oracle ms to state 95% intervals that small</th>")
      << "</tr>";
    for (size_t b = 0; b < budgets.size(); ++b) {
        const double budget = budgets[b];
        const std::optional<size_t>& best = cheapest[b];
        s << "<tr><td>" << num(budget, 3) << "</td><td>"
          << (best ? html(d.points[*best].label) : "none") << "</td><td>"
          << (best ? withUnit(cost, d.points[*best].cost / displayScale(cost)) : "–") << "</td>";
        if (!d.oracle.empty()) {
            const std::optional<double> ms = oracleMsAtError(d.oracle, budget);
            s << "<td>" << (ms ? num(*ms, 3) : "not within its run") << "</td>";
        }
        s << "</tr>";
    }
    s << "</table>";
    if (d.exact)
        s << "<p class=\"caption\">The oracle's exact pass gave " << d.exact->pixels
          << " pixels their V without sampling error (any budget) in " << num(d.exact->ms, 3)
          << " ms: the sampled pass that found them and " << num(d.exact->exactMs, 3)
          << " ms of clipping.</p>";
    s << "</div>";
    return s.str();
}

// A table of rows (technique x light) over the given numeric columns, sortable, best marked.
void writeMetricTable(std::ostream& o, const std::string& attrs,
                      const std::vector<const ReportTechnique*>& techniques,
                      const std::vector<size_t>& lights, const std::vector<const Column*>& cols,
                      const ReportInput& in) {
    std::vector<const LightRow*> rows;
    for (const ReportTechnique* t : techniques)
        for (size_t li : lights) rows.push_back(&lightRow(*t, in, li));
    std::vector<std::vector<std::string>> cells;
    for (const Column* c : cols) cells.push_back(columnCells(*c->metric, rows));
    o << "<table " << attrs
      << "><thead><tr><th data-col=\"label\" class=\"text\" title=\"the setting as given; "
         "hover for all its parameters\">technique</th><th data-col=\"family\" "
         "class=\"text\">family</th>"
      << (lights.size() > 1 ? "<th data-col=\"light\" class=\"text\">light</th>" : "");
    for (const Column* c : cols) o << headerCell(*c->metric);
    o << "<th class=\"text\">timing</th></tr></thead><tbody>";
    size_t r = 0;
    for (const ReportTechnique* t : techniques)
        for (size_t li : lights) {
            o << "<tr><td class=\"text\" title=\"" << html(t->parameters) << "\"><a href=\"#"
              << rowId(li, size_t(t - in.techniques.data())) << "\">" << html(t->row.label)
              << "</a>" << fidelityMark(t->row.fidelity, t->row.provenanceText)
              << historyMark(t->row.historyFrames) << "</td><td class=\"text\">"
              << html(t->row.family) << "</td>";
            if (lights.size() > 1) o << "<td class=\"text\">" << html(in.lights[li]) << "</td>";
            for (size_t c = 0; c < cols.size(); ++c) o << cells[c][r];
            const bool noisy = rows[r]->value("cost.noisy").value_or(0.0) != 0.0;
            o << "<td class=\"text\">" << (noisy ? "<i>noisy</i>" : "") << "</td></tr>";
            ++r;
        }
    o << "</tbody></table>";
}

}  // namespace

// Per light: the summary columns that have a value for some technique.
void writeSummary(std::ostream& o, const ReportInput& in, size_t li) {
    std::vector<const Column*> cols;
    for (const Column& c : columns()) {
        if (c.inSummary && anyValue(in, li, *c.metric)) cols.push_back(&c);
    }
    o << "<div class=\"summary-col\"><h3>Summary</h3><p class=\"muted\">Click a column to sort; "
         "&#9733; marks the best "
         "per column (lower is better; for the bias, nearer zero). Hover a header for its "
         "definition, a technique for its parameters.</p>";
    o << "<div class=\"summary-wrap\">";
    writeMetricTable(o, "class=\"sortable summary\"", byFamily(in), {li}, cols, in);
    o << "</div></div>";
}

// The data the script draws one light's chart from (report_assets.h).
nlohmann::json lightData(const ReportInput& in, size_t li) {
    const std::vector<ChartChoice> errors = chartChoices(in, li, false),
                                   costs = chartChoices(in, li, true);
    auto values = [&](const std::vector<ChartChoice>& choices, const LightRow& l) {
        nlohmann::json v = nlohmann::json::object();
        for (const ChartChoice& c : choices)
            if (const auto x = l.value(*c.metric)) v[c.key] = *x * displayScale(*c.metric);
        return v;
    };
    auto names = [](const std::vector<ChartChoice>& choices) {
        nlohmann::json n = nlohmann::json::array();
        for (const ChartChoice& c : choices) n.push_back({c.key, c.name});
        return n;
    };
    nlohmann::json points = nlohmann::json::array();
    for (size_t k = 0; k < in.techniques.size(); ++k) {
        const ReportTechnique& t = in.techniques[k];
        const LightRow& row = lightRow(t, in, li);
        const nlohmann::json e = values(errors, row), c = values(costs, row);
        points.push_back({{"label", t.row.label},
                          {"curve", t.curve},
                          {"quality", t.quality ? nlohmann::json(*t.quality) : nlohmann::json()},
                          {"row", rowId(li, k)},
                          {"e", e},
                          {"c", c}});
    }
    nlohmann::json oracle = nlohmann::json::array();
    if (li < in.oracleCurves.size())
        for (const auto& [ms, hw] : in.oracleCurves[li])
            if (ms > 0.0 && hw > 0.0) oracle.push_back({ms, hw});
    nlohmann::json exact;  // null where the exact pass did not apply
    if (li < in.oracleExact.size() && in.oracleExact[li])
        exact = {{"ms", in.oracleExact[li]->ms},
                 {"exact_ms", in.oracleExact[li]->exactMs},
                 {"pixels", in.oracleExact[li]->pixels}};
    return {{"name", in.lights[li]},
            {"errors", names(errors)},
            {"costs", names(costs)},
            {"points", points},
            {"oracle", oracle},
            {"oracle_exact", exact},
            {"oracle_error", "penumbra_mae"}};
}

// `d`: the light's lightData, the same the page's script draws from.
void writeChartBox(std::ostream& o, const ReportInput& in, size_t li, const nlohmann::json& d) {
    // data-exact: the test harness (tests/browser) looks for the exact pass's point where it is
    // set.
    o << "<div class=\"chart-box\" data-light=\"" << li << "\""
      << (d["oracle_exact"].is_null() ? "" : " data-exact=\"1\"") << "><h3>Error against cost</h3>"
      << "<label>error <select class=\"error-select\">";
    for (const auto& e : d["errors"])
        o << "<option value=\"" << html(e[0]) << "\">" << html(e[1]) << "</option>";
    o << "</select></label><label>cost <select class=\"cost-select\">";
    for (const auto& c : d["costs"])
        o << "<option value=\"" << html(c[0]) << "\">" << html(c[1]) << "</option>";
    o << "</select></label><br><svg class=\"chart\" viewBox=\"0 0 640 360\" width=\"640\" "
         "height=\"360\" role=\"img\" aria-label=\"error against cost\"></svg>"
      << "<p class=\"caption\"></p>";
    bool first = true;
    for (const ChartChoice& c : chartChoices(in, li, true)) {
        const std::string table = budgetTable(chartData(in, li, c), first);
        first = first && table.empty();
        o << table;
    }
    o << "</div>";
}

void writeContactPairs(std::ostream& o, const ReportInput& in, size_t li) {
    std::vector<ContactSetting> settings;
    for (const ReportTechnique& t : in.techniques)
        settings.push_back({&t.row, &lightRow(t, in, li)});
    writeContactTable(o, pairContactSettings(settings));
}

void writeAllMetrics(std::ostream& o, const ReportInput& in) {
    std::vector<size_t> lights;
    for (size_t li = 0; li < in.lights.size(); ++li) lights.push_back(li);
    std::vector<const Column*> cols;
    // A run without a camera path (a sequence) has no temporal (sequence) metric at all: no empty
    // column for it.
    for (const Column& c : columns()) {
        const std::string name = c.metric->name;
        if ((in.pathFrames > 0 || name.rfind("temporal_", 0) != 0) &&
            (in.sequenceFrames > 0 || name.rfind("sequence.", 0) != 0))
            cols.push_back(&c);
    }
    writeMetricTable(o, "class=\"sortable\" id=\"metrics\"", byFamily(in), lights, cols, in);
}

bool hasPenumbra(const ReportInput& in, size_t li) {
    return anyValue(in, li, metricInfo("penumbra_mae"));
}

std::string withUnit(const MetricInfo& m, double v) {
    const std::string unit = m.unit == MetricUnit::Count ? "" : displayUnit(m);
    return formatMetricValue(m, v) + (unit.empty() ? "" : " " + unit);
}

}  // namespace so::report_parts
