#include "raster_compare/compare/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/channels.h"
#include "core/error.h"
#include "raster_compare/compare/artifacts.h"
#include "raster_compare/compare/contact_pairs.h"
#include "raster_compare/compare/html.h"
#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/report_assets.h"
#include "raster_compare/compare/report_images.h"
#include "raster_compare/compare/tradeoff.h"

namespace so {

namespace {

namespace ch = channels;

std::string html(const std::string& s) {
    return htmlEscape(s);
}

std::string num(std::optional<double> v, int digits = 4) {
    if (!v) return "–";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, *v);
    return buf;
}

// A numeric column of the tables: its metric key (docs/metrics.md) and how to read it from a
// typed row. Its header, meaning, number format and which way is better are the metric table's
// (metric_table.h), so the report and docs/metrics.md say the same.
struct Column {
    std::string key;
    std::function<std::optional<double>(const LightComparison&)> value;
    bool inSummary = true;
};

std::optional<double> median(const std::optional<TimingStats>& t) {
    return t ? std::optional(t->median) : std::nullopt;
}

std::optional<double> workCount(const LightComparison& l, uint64_t WorkCounts::*count) {
    return l.cost.work ? std::optional(double((*l.cost.work).*count)) : std::nullopt;
}

const std::vector<Column>& columns() {
    using L = const LightComparison&;
    static const std::vector<Column> cols = {
        {"mae", [](L l) { return std::optional(l.metrics.mae); }},
        {"acne_rate", [](L l) { return std::optional(l.metrics.acneRate); }},
        {"penumbra_spread_rate", [](L l) { return l.metrics.penumbraSpreadRate; }},
        {"peter_panning_rate", [](L l) { return l.metrics.peterPanningRate; }},
        {"boundary_displacement_px.p95",
         [](L l) { return std::optional(l.metrics.boundaryDisplacement.p95); }},
        {"aliasing_rate", [](L l) { return l.metrics.aliasingRate; }, false},
        {"light_bleeding_rate", [](L l) { return l.metrics.lightBleedingRate; }},
        {"penumbra_mae", [](L l) { return l.metrics.penumbraMae; }},
        {"penumbra_bias", [](L l) { return l.metrics.penumbraBias; }},
        {"penumbra_width_error_px.mean",
         [](L l) {
             return l.metrics.penumbraWidth ? std::optional(l.metrics.penumbraWidth->mean)
                                            : std::nullopt;
         }},
        {"temporal_flicker_rate",
         [](L l) { return l.temporal ? l.temporal->rate() : std::nullopt; }},
        {"sequence.mae_mean",
         [](L l) { return l.sequence ? std::optional(l.sequence->maeMean()) : std::nullopt; }},
        {"sequence.flicker_rate",
         [](L l) { return l.sequence ? l.sequence->flicker.rate() : std::nullopt; }},
        {"sequence.lag_mae", [](L l) { return l.sequence ? l.sequence->lagMae() : std::nullopt; }},
        {"false_shadow_rate", [](L l) { return std::optional(l.metrics.falseShadowRate); }, false},
        {"false_lit_rate", [](L l) { return std::optional(l.metrics.falseLitRate); }, false},
        {"cost.frame_ms", [](L l) { return median(l.cost.frameMs); }},
        {"cost.shadow_map_ms", [](L l) { return median(l.cost.shadowMapMs); }},
        {"cost.visibility_ms", [](L l) { return median(l.cost.visibilityMs); }},
        {"cost.camera_ms", [](L l) { return median(l.cost.cameraMs); }},
        {"cost.memory_bytes",
         [](L l) {
             return l.cost.memoryBytes ? std::optional(double(*l.cost.memoryBytes)) : std::nullopt;
         }},
        {"cost.work.fragments", [](L l) { return workCount(l, &WorkCounts::fragments); }},
        {"cost.work.texture_taps", [](L l) { return workCount(l, &WorkCounts::textureTaps); },
         false},
        {"cost.work.texels_written", [](L l) { return workCount(l, &WorkCounts::texelsWritten); },
         false},
        {"cost.work.bytes_moved", [](L l) { return workCount(l, &WorkCounts::bytesMoved); }},
        {"cost.work.draw_calls", [](L l) { return workCount(l, &WorkCounts::drawCalls); }, false},
        {"cost.work.passes", [](L l) { return workCount(l, &WorkCounts::passes); }, false},
        {"cost.work.rays_traced", [](L l) { return workCount(l, &WorkCounts::raysTraced); }, false},
        {"cost.oracle_ms_at_equal_error", [](L l) { return l.cost.oracleMsAtEqualError; }, false},
    };
    return cols;
}

const Column& findColumn(const std::string& key) {
    for (const Column& c : columns())
        if (c.key == key) return c;
    throw std::logic_error("report: no column " + key);
}

// Whether some technique has a value in the column for the light.
bool anyValue(const ReportInput& in, size_t li, const Column& c) {
    return std::any_of(in.techniques.begin(), in.techniques.end(),
                       [&](const ReportTechnique& t) { return c.value(t.lights[li]).has_value(); });
}

// An area light's page: its techniques have a penumbra error.
bool hasPenumbra(const ReportInput& in, size_t li) {
    return anyValue(in, li, findColumn("penumbra_mae"));
}

// The metric table's entry of a column; a key missing there is a bug, found by any test that
// writes a report.
const MetricInfo& tableEntry(const Column& c) {
    const MetricInfo* info = findMetric(c.key);
    SO_CHECK(info != nullptr);
    return *info;
}

// "frame time (ms)", "acne": the label, and the unit its values are shown in (a count's is not
// said).
std::string titleWithUnit(const MetricInfo& m) {
    const std::string unit = m.unit == MetricUnit::Count ? "" : displayUnit(m);
    return metricLabel(m) + (unit.empty() ? "" : " (" + unit + ")");
}

// The value with its unit, where the column's header would say it: "12.3 ms", "195.48 MiB".
std::string withUnit(const MetricInfo& m, double v) {
    const std::string unit = m.unit == MetricUnit::Count ? "" : displayUnit(m);
    return formatMetricValue(m, v) + (unit.empty() ? "" : " " + unit);
}

// The header cell of a numeric column: sortable, with its direction and meaning as a tooltip (a
// signed column's tip says itself that nearer zero is better).
std::string headerCell(const Column& c) {
    const MetricInfo& m = tableEntry(c);
    const std::string direction = m.better == Better::Lower    ? "; lower is better"
                                  : m.better == Better::Higher ? "; higher is better"
                                                               : "";
    return "<th data-col=\"" + html(c.key) + "\" title=\"" + html(c.key) + ": " +
           html(m.description) + direction + " (docs/metrics.md)\">" + html(titleWithUnit(m)) +
           "</th>";
}

// The cells of one column over rows, the best (least, or nearest zero) marked; none in a column
// whose metric has no better direction (the oracle's time at equal error).
std::vector<std::string> columnCells(const Column& c,
                                     const std::vector<const LightComparison*>& rows) {
    std::optional<double> best;
    const Better better = tableEntry(c).better;
    auto score = [&](double v) {
        return better == Better::SmallerMagnitude ? std::fabs(v)
               : better == Better::Higher         ? -v
                                                  : v;
    };
    for (const LightComparison* l : rows)
        if (const auto v = c.value(*l); v && (!best || score(*v) < *best)) best = score(*v);
    std::vector<std::string> cells;
    for (const LightComparison* l : rows) {
        const std::optional<double> v = c.value(*l);
        char data[40] = "";
        if (v) std::snprintf(data, sizeof data, "%.9g", *v);
        const bool isBest = v && rows.size() > 1 && better != Better::None && score(*v) == *best;
        cells.push_back(std::string("<td data-v=\"") + data + "\"" +
                        (isBest ? " class=\"best\"" : "") + ">" +
                        (v ? formatMetricValue(tableEntry(c), *v) : "–") + "</td>");
    }
    return cells;
}
// The error and cost a chart can plot: those with a value for some technique of the light, as
// (key, name, column).
struct ChartChoice {
    std::string key, name;
    const Column* column;
};

std::vector<ChartChoice> chartChoices(const ReportInput& in, size_t li, bool costs) {
    static const std::vector<std::string> errors = {"penumbra_mae",
                                                    "mae",
                                                    "acne_rate",
                                                    "peter_panning_rate",
                                                    "boundary_displacement_px.p95",
                                                    "light_bleeding_rate",
                                                    "temporal_flicker_rate"};
    static const std::vector<std::string> cost = {
        "frame_ms",        "shadow_map_ms",     "visibility_ms",       "memory_bytes",
        "work.fragments",  "work.texture_taps", "work.texels_written", "work.bytes_moved",
        "work.draw_calls", "work.passes",       "work.rays_traced"};
    std::vector<ChartChoice> out;
    for (const std::string& key : costs ? cost : errors) {
        const Column& c = findColumn(costs ? "cost." + key : key);
        if (anyValue(in, li, c)) out.push_back({key, titleWithUnit(tableEntry(c)), &c});
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
        const LightMetrics& m = t.lights[light].metrics;
        if (area && !m.penumbraMae) continue;
        // An external image without that cost (or a technique without a time) has no point.
        const std::optional<double> c = cost.column->value(t.lights[light]);
        if (!c) continue;
        d.points.push_back({t.label, t.curve, t.quality,
                            *c * displayScale(tableEntry(*cost.column)),
                            area ? *m.penumbraMae : m.mae});
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
    const MetricInfo& cost = tableEntry(*d.cost.column);
    std::ostringstream s;
    s << "<div class=\"budget-box\" data-cost=\"" << html(d.cost.key) << "\""
      << (shown ? "" : " hidden") << "><p class=\"caption\">Read off at error budgets ("
      << html(d.error) << " against " << html(d.cost.name)
      << "):</p><table class=\"budget\"><tr><th>" << html(d.error)
      << " at most</th><th>cheapest setting</th><th>its cost</th>"
      << (d.oracle.empty() ? "" : "<th>oracle ms to state 95% intervals that small</th>")
      << "</tr>";
    for (double budget : {0.2, 0.1, 0.05, 0.02, 0.01, 0.005}) {
        const std::optional<size_t> best = cheapestWithin(d.points, budget);
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

// The techniques grouped by family, families in the order they first appear, techniques in the
// order given within each.
std::vector<const ReportTechnique*> byFamily(const ReportInput& in) {
    std::vector<const ReportTechnique*> ordered;
    for (const ReportTechnique& first : in.techniques) {
        bool seen = false;
        for (const ReportTechnique* t : ordered) seen |= t->family == first.family;
        if (seen) continue;
        for (const ReportTechnique& t : in.techniques)
            if (t.family == first.family) ordered.push_back(&t);
    }
    return ordered;
}

std::string lightId(const ReportInput& in, size_t li) {
    return "light-" + in.lights[li];
}
std::string rowId(size_t li, size_t k) {
    return "row-" + std::to_string(li) + "-" + std::to_string(k);
}

// A table of rows (technique x light) over the given numeric columns, sortable, best marked.
void writeMetricTable(std::ostream& o, const std::string& attrs,
                      const std::vector<const ReportTechnique*>& techniques,
                      const std::vector<size_t>& lights, const std::vector<const Column*>& cols,
                      const ReportInput& in) {
    std::vector<const LightComparison*> rows;
    for (const ReportTechnique* t : techniques)
        for (size_t li : lights) rows.push_back(&t->lights[li]);
    std::vector<std::vector<std::string>> cells;
    for (const Column* c : cols) cells.push_back(columnCells(*c, rows));
    o << "<table " << attrs
      << "><thead><tr><th data-col=\"label\" class=\"text\" title=\"the setting as given; "
         "hover for all its parameters\">technique</th><th data-col=\"family\" "
         "class=\"text\">family</th>"
      << (lights.size() > 1 ? "<th data-col=\"light\" class=\"text\">light</th>" : "");
    for (const Column* c : cols) o << headerCell(*c);
    o << "<th class=\"text\">timing</th></tr></thead><tbody>";
    size_t r = 0;
    for (const ReportTechnique* t : techniques)
        for (size_t li : lights) {
            o << "<tr><td class=\"text\" title=\"" << html(t->parameters) << "\"><a href=\"#"
              << rowId(li, size_t(t - in.techniques.data())) << "\">" << html(t->label)
              << "</a></td><td class=\"text\">" << html(t->family) << "</td>";
            if (lights.size() > 1) o << "<td class=\"text\">" << html(in.lights[li]) << "</td>";
            for (size_t c = 0; c < cols.size(); ++c) o << cells[c][r];
            o << "<td class=\"text\">" << (t->lights[li].cost.noisy() ? "<i>noisy</i>" : "")
              << "</td></tr>";
            ++r;
        }
    o << "</tbody></table>";
}

// Per light: the summary columns that have a value for some technique.
void writeSummary(std::ostream& o, const ReportInput& in, size_t li) {
    std::vector<const Column*> cols;
    for (const Column& c : columns()) {
        if (c.inSummary && anyValue(in, li, c)) cols.push_back(&c);
    }
    o << "<div class=\"summary-col\"><h3>Summary</h3><p class=\"muted\">Click a column to sort; "
         "&#9733; marks the best "
         "per column (lower is better; for the bias, nearer zero). Hover a header for its "
         "definition, a technique for its parameters.</p>";
    o << "<div class=\"summary-wrap\">";
    writeMetricTable(o, "class=\"sortable summary\"", byFamily(in), {li}, cols, in);
    o << "</div></div>";
}

// Light li's contact=on settings against their contact=off ones (contact_pairs.h).
std::vector<ContactPair> contactPairs(const ReportInput& in, size_t li) {
    std::vector<ContactSetting> settings;
    for (const ReportTechnique& t : in.techniques)
        settings.push_back(
            {t.label, t.technique, t.settings, contactRatesOf(t.lights[li].metrics)});
    return pairContactSettings(settings);
}

// The data the script draws one light's chart from (report_assets.h).
nlohmann::json lightData(const ReportInput& in, size_t li) {
    const std::vector<ChartChoice> errors = chartChoices(in, li, false),
                                   costs = chartChoices(in, li, true);
    auto values = [&](const std::vector<ChartChoice>& choices, const LightComparison& l) {
        nlohmann::json v = nlohmann::json::object();
        for (const ChartChoice& c : choices)
            if (const auto x = c.column->value(l))
                v[c.key] = *x * displayScale(tableEntry(*c.column));
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
        const nlohmann::json e = values(errors, t.lights[li]), c = values(costs, t.lights[li]);
        points.push_back({{"label", t.label},
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

// The classes' colours, beside the error maps.
std::string classLegend() {
    std::ostringstream o;
    o << "<div class=\"legend\">";
    for (const ArtifactClass& c : kArtifactClasses)
        o << "<span><i style=\"background:rgb(" << int(c.rgb[0] * 255) << "," << int(c.rgb[1] * 255)
          << "," << int(c.rgb[2] * 255) << ")\"></i>" << c.legend << "</span>";
    o << "<span>grey: right (the truth, dimmed)</span></div>";
    return o.str();
}

std::string zoomable(const std::string& src, const std::string& alt, const std::string& id,
                     const std::string& oracleId) {
    return "<img class=\"zoomable\" src=\"" + src + "\" alt=\"" + html(alt) + "\"" +
           (id.empty() ? "" : " id=\"" + id + "\"") + " data-oracle=\"" + oracleId +
           "\" loading=\"lazy\">";
}

// The oracle's row: its render, the predicted aliasing (once: the first technique's that has
// it) and the pixels it left short of its target.
void writeOracleRow(std::ostream& o, const ReportInput& in, size_t li, ImageSink& sink,
                    const std::string& oracleId, const Rgb& oracleRender) {
    const int w = in.oracle.width(), h = in.oracle.height();
    const std::string& light = in.lights[li];
    const std::string l = std::to_string(li);
    o << "<tr><td><b>oracle</b><br><span class=\"muted\">the ground truth (<a "
         "href=\"oracle.exr\">oracle.exr</a>)</span></td><td>"
      << zoomable(sink.src("l" + l + "_oracle", w, h, oracleRender), "oracle", oracleId, oracleId)
      << "</td><td>";
    for (const ReportTechnique& t : in.techniques) {
        if (!t.image.has(ch::lightChannel(light, ch::kPredictedAliasing))) continue;
        o << zoomable(sink.src("l" + l + "_aliasing", w, h, aliasingMap(t.image, light)),
                      "predicted aliasing of " + t.label, "", oracleId)
          << "<span class=\"muted\">predicted aliasing of " << html(t.label)
          << ": texel over pixel footprint, blue &lt; 1 (white) &lt; red</span>";
        break;
    }
    o << "</td><td colspan=\"2\">";
    size_t count = 0;
    const Rgb unconverged = unconvergedMap(in.oracle, light, count);
    if (count)
        o << zoomable(sink.src("l" + l + "_unconverged", w, h, unconverged),
                      "oracle pixels short of the target", "", oracleId)
          << "<span class=\"muted\">" << count
          << " oracle pixels spent their sample budget before reaching the target (orange): "
             "their intervals are wider</span>";
    o << "</td></tr>";
}

// One technique's row: its render, its error map by class (and on area lights by magnitude), the
// worst square of its error map next to the oracle's, and its files.
void writeTechniqueRow(std::ostream& o, const ReportInput& in, size_t li, size_t k, ImageSink& sink,
                       const std::string& oracleId, const Rgb& oracleRender) {
    const ReportTechnique& t = in.techniques[k];
    const LightComparison& lc = t.lights[li];
    const int w = in.oracle.width(), h = in.oracle.height();
    const std::string& light = in.lights[li];
    const std::string key = "l" + std::to_string(li) + "_" + t.fileLabel;
    const Rgb render =
        shadedImage(in.oracle, t.image.channel(ch::lightChannel(light, ch::kVisibility)), light);
    o << "<tr id=\"" << rowId(li, k) << "\"><td><b>" << html(t.label)
      << "</b><br><span class=\"muted\">" << html(t.family) << "<br>" << html(t.parameters)
      << "<br>mae " << num(lc.metrics.mae) << ", frame "
      << (lc.cost.frameMs ? withUnit(*findMetric("cost.frame_ms"), lc.cost.frameMs->median)
                          : "unknown")
      << "<br><a href=\"" << html(t.fileLabel) << "/raster.exr\">raster.exr</a> · <a href=\""
      << html(t.fileLabel) << "/raster.json\">raster.json</a> · <a href=\"error_"
      << html(t.fileLabel) << ".exr\">errors</a></span></td><td>"
      << zoomable(sink.src(key + "_render", w, h, render), t.label, "", oracleId) << "</td><td>"
      << zoomable(sink.src(key + "_classes", w, h, classMap(in.oracle, lc.maps, light)),
                  t.label + " errors by class", "", oracleId)
      << "</td><td>";
    if (lc.metrics.penumbraMae)
        o << zoomable(sink.src(key + "_magnitude", w, h, magnitudeMap(in.oracle, lc.maps)),
                      t.label + " error magnitude", "", oracleId);
    const Crop crop = worstRegion(lc.maps.error, w, h, std::max(16, std::min(w, h) / 6));
    o << "</td><td>"
      << "<img class=\"crop\" src=\""
      << sink.src(key + "_worst", crop.size, crop.size, cropOf(render, w, crop)) << "\" alt=\""
      << html(t.label) << " worst region\"><img class=\"crop\" src=\""
      << sink.src(key + "_worst_oracle", crop.size, crop.size, cropOf(oracleRender, w, crop))
      << "\" alt=\"oracle, same region\"><br><span class=\"muted\">at (" << crop.x << ", " << crop.y
      << "): technique, oracle</span></td></tr>";
}

void writeImages(std::ostream& o, const ReportInput& in, size_t li, ImageSink& sink) {
    const bool area = hasPenumbra(in, li);
    o << "<h3>Images</h3><p class=\"muted\">Click an image for a 1:1, 2x or 4x view; F flips it "
         "with the oracle's at the same place.</p>";
    if (area) o << oracleCertaintyNote(in.oracle, in.lights[li]);
    const std::string oracleId = "oracle-" + std::to_string(li);
    o << "<table class=\"images\"><thead><tr><th class=\"text\">technique</th><th "
         "class=\"text\">render</th><th class=\"text\">errors by class"
      << classLegend() << "</th><th class=\"text\">"
      << (area ? "error beyond the oracle's interval" + magnitudeBar() : std::string())
      << "</th><th class=\"text\">worst region</th></tr></thead><tbody>";
    const std::string& light = in.lights[li];
    const Rgb oracleRender =
        shadedImage(in.oracle, in.oracle.channel(ch::lightChannel(light, ch::kVisibility)), light);
    writeOracleRow(o, in, li, sink, oracleId, oracleRender);
    for (const ReportTechnique* t : byFamily(in))
        writeTechniqueRow(o, in, li, size_t(t - in.techniques.data()), sink, oracleId,
                          oracleRender);
    o << "</tbody></table>";
}

// compare --frames-path: the worst technique's worst pair of frames, the flickering pixels red.
void writeFlickerStrip(std::ostream& o, const ReportInput& in, size_t li, ImageSink& sink) {
    if (in.pathFrames == 0 || li >= in.flickerStrips.size()) return;
    o << "<h3>Temporal flicker</h3>";
    const std::optional<FlickerStrip>& s = in.flickerStrips[li];
    if (!s || s->flickering == 0) {
        o << "<p class=\"muted\">No technique flickers along the camera path (" << in.pathFrames
          << " frames).</p>";
        return;
    }
    const std::string key = "flicker_" + std::to_string(li);
    const auto img = [&](const std::string& k, const Rgb& rgb, const std::string& caption) {
        o << "<figure><img src=\"" << sink.src(key + k, s->width, s->height, rgb) << "\" alt=\""
          << html(caption) << "\"><figcaption class=\"muted\">" << html(caption)
          << "</figcaption></figure>";
    };
    o << "<p>The highest temporal_flicker_rate along the camera path (" << in.pathFrames
      << " frames): <b>" << html(s->technique) << "</b>, "
      << formatMetricValue(*findMetric("temporal_flicker_rate"), s->rate) << ". Its worst pair, "
      << "frames " << s->pair << " and " << s->pair + 1 << ", has " << s->flickering
      << " flickering pixels (red; dimmed: not tracked).</p><div class=\"flicker-strip\" "
         "id=\"flicker-strip-"
      << li << "\">";
    img("_prev", visibilityGrey(s->vPrev), "frame " + std::to_string(s->pair) + ": V");
    img("_next", visibilityGrey(s->vNext), "frame " + std::to_string(s->pair + 1) + ": V");
    img("_marked", flickerMap(s->vNext, s->mask),
        "frame " + std::to_string(s->pair + 1) + ": flickering pixels");
    img("_oracle", visibilityGrey(s->vOracleNext),
        "frame " + std::to_string(s->pair + 1) + ": the oracle's V");
    o << "</div>";
}

// compare --sequence: every technique's mae at each frame of the sequence, one line each, drawn
// as SVG on the server (no script): frames along x, mae from 0 up along y.
void writeSequenceChart(std::ostream& o, const ReportInput& in, size_t li) {
    if (in.sequenceFrames == 0) return;
    static const char* kColours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                     "#e69f00", "#56b4e9", "#000000", "#999999"};
    constexpr double kW = 640, kH = 260, kLeft = 68, kRight = 16, kTop = 12, kBottom = 36;
    const int frames = in.sequenceFrames;
    double top = 0.0;
    for (const ReportTechnique& t : in.techniques)
        if (const auto& s = t.lights[li].sequence)
            for (double e : s->maePerFrame) top = std::max(top, e);
    top = top > 0.0 ? top * 1.1 : 1.0;
    const auto x = [&](int f) {
        return kLeft + (kW - kLeft - kRight) * (frames > 1 ? double(f) / (frames - 1) : 0.5);
    };
    const auto y = [&](double e) { return kH - kBottom - (kH - kTop - kBottom) * e / top; };
    o << "<h3>Error per frame</h3><div class=\"sequence-box\" id=\"sequence-" << li
      << "\"><svg class=\"chart\" viewBox=\"0 0 " << kW << " " << kH << "\" width=\"" << kW
      << "\" height=\"" << kH << "\" role=\"img\" aria-label=\"mae per frame\">";
    for (int k = 0; k <= 4; ++k) {
        const double e = top * k / 4.0;
        o << "<line class=\"grid\" x1=\"" << kLeft << "\" x2=\"" << kW - kRight << "\" y1=\""
          << y(e) << "\" y2=\"" << y(e) << "\"/><text x=\"" << kLeft - 4 << "\" y=\"" << y(e) + 4
          << "\" text-anchor=\"end\">" << num(e, 3) << "</text>";
    }
    for (int f = 0; f < frames; f += std::max(1, frames / 8))
        o << "<text x=\"" << x(f) << "\" y=\"" << kH - kBottom + 14 << "\" text-anchor=\"middle\">"
          << f << "</text>";
    o << "<line class=\"axis\" x1=\"" << kLeft << "\" x2=\"" << kW - kRight << "\" y1=\"" << y(0)
      << "\" y2=\"" << y(0) << "\"/><text class=\"label\" x=\"" << (kLeft + kW - kRight) / 2
      << "\" y=\"" << kH - 4
      << "\" text-anchor=\"middle\">frame</text><text class=\"label\" "
      // Upright beside the tick labels, so that it never overlaps the top one.
      << "transform=\"rotate(-90)\" x=\"" << -(kTop + kH - kBottom) / 2
      << "\" y=\"12\" text-anchor=\"middle\">mae</text>";
    std::ostringstream legend;
    size_t colour = 0;
    for (const ReportTechnique* t : byFamily(in)) {
        const auto& s = t->lights[li].sequence;
        if (!s) continue;
        const char* c = kColours[colour++ % std::size(kColours)];
        o << "<polyline class=\"series\" stroke=\"" << c << "\" points=\"";
        for (size_t f = 0; f < s->maePerFrame.size(); ++f)
            o << (f ? " " : "") << x(int(f)) << "," << y(s->maePerFrame[f]);
        o << "\"><title>" << html(t->label) << "</title></polyline>";
        legend << "<span><i style=\"background:" << c << "\"></i>" << html(t->label) << "</span>";
    }
    o << "</svg><div class=\"legend\">" << legend.str() << "</div><p class=\"caption muted\">mae "
      << "of each of the " << frames << " frames against that frame's oracle "
      << "(docs/metrics.md#sequence); the rows above judge the last frame.</p></div>";
}

void writeHead(std::ostream& o, const ReportInput& in) {
    o << "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadow-oracle "
         "report: "
      << html(in.sceneFile) << "</title><style>" << report_assets::kStyle
      << "</style></head><body><h1>Shadow accuracy against the oracle: " << html(in.sceneFile)
      << "</h1><p>" << in.techniques.size() << " technique settings, " << in.lights.size()
      << " light" << (in.lights.size() == 1 ? "" : "s") << ". Times were measured on <b>"
      << html(in.timedOn) << "</b>";
    if (in.timedOn.find("llvmpipe") != std::string::npos)
        o << " (Mesa's CPU rasterizer: its times rank the techniques on this machine, not on a "
             "GPU)";
    o << "; medians over the timed frames, the techniques taking turns frame by frame. Files: "
         "<a href=\"metrics.json\">metrics.json</a> · <a href=\"metrics.csv\">metrics.csv</a> · "
         "<a href=\"metrics_wide.csv\">metrics_wide.csv</a> · <a "
         "href=\"oracle.exr\">oracle.exr</a>.</p><nav>Lights:";
    for (size_t li = 0; li < in.lights.size(); ++li)
        o << " <a href=\"#" << html(lightId(in, li)) << "\">" << html(in.lights[li]) << "</a>";
    o << " <a href=\"#all-metrics\">all metrics</a> <a href=\"#provenance\">provenance</a></nav>";
}

// `lightsData`: every light's lightData, in order.
void writeTail(std::ostream& o, const ReportInput& in, const nlohmann::json& lightsData) {
    o << "<h2 id=\"all-metrics\">All metrics</h2>";
    std::vector<size_t> lights;
    for (size_t li = 0; li < in.lights.size(); ++li) lights.push_back(li);
    std::vector<const Column*> cols;
    // A run without a camera path (a sequence) has no temporal (sequence) metric at all: no empty
    // column for it.
    for (const Column& c : columns())
        if ((in.pathFrames > 0 || c.key.rfind("temporal_", 0) != 0) &&
            (in.sequenceFrames > 0 || c.key.rfind("sequence.", 0) != 0))
            cols.push_back(&c);
    writeMetricTable(o, "class=\"sortable\" id=\"metrics\"", byFamily(in), lights, cols, in);
    o << "<h2 id=\"provenance\">Provenance</h2><table class=\"provenance\">";
    for (const auto& [key, value] : in.provenance)
        o << "<tr><th class=\"text\">" << html(key) << "</th><td class=\"text\">" << html(value)
          << "</td></tr>";
    o << "</table><div id=\"zoom\"><div class=\"bar\"><span id=\"zoom-title\"></span><button "
         "id=\"zoom-flip\">flip with the oracle (F)</button><label>scale <select "
         "id=\"zoom-scale\"><option>1</option><option selected>2</option><option>4</option>"
         "</select></label><button id=\"zoom-close\">close (Esc)</button></div><div "
         "class=\"view\"><canvas id=\"zoom-canvas\"></canvas></div></div>";
    std::string json = nlohmann::json({{"lights", lightsData}}).dump();
    for (size_t at = json.find("</"); at != std::string::npos; at = json.find("</", at + 2))
        json.replace(at, 2, "<\\/");
    o << "<script type=\"application/json\" id=\"so-data\">" << json << "</script><script>"
      << report_assets::kScript << "</script></body></html>\n";
}

}  // namespace

std::string oracleCertaintyNote(const ChannelImage& oracle, const std::string& light) {
    const std::string stdErrName = ch::lightChannel(light, ch::kStdErr);
    const std::string exactName = ch::lightChannel(light, ch::kExact);
    const float* stdErr = oracle.has(stdErrName) ? oracle.channel(stdErrName) : nullptr;
    const float* exact = oracle.has(exactName) ? oracle.channel(exactName) : nullptr;
    size_t sampled = 0, exactPixels = 0;
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        if (exact && exact[i] > 0.5f)
            ++exactPixels;
        else if (stdErr && stdErr[i] > 0.0f)
            ++sampled;
    }
    const std::string interval =
        "an estimate with a 95% interval per pixel (V &plusmn; 2.36 &middot; stderr, "
        "docs/oracle.md); a technique's difference within that interval is not counted as error, "
        "and the magnitude map shows the error beyond it";
    std::ostringstream s;
    s << "<p class=\"note\">An area light: ";
    if (exactPixels == 0)
        s << "the oracle's V is " << interval << ".</p>";
    else if (sampled == 0)
        s << "the oracle's exact pass gave V at all " << exactPixels
          << " pixels it applied to, without sampling error (docs/oracle.md, \"Exact "
             "penumbrae\"); no pixel of this light carries a sampling interval.</p>";
    else
        s << "the oracle's exact pass gave V without sampling error at " << exactPixels
          << " pixels (docs/oracle.md, \"Exact penumbrae\"); at the other " << sampled
          << " penumbra pixels it is " << interval << ".</p>";
    return s.str();
}

void writeReport(const std::string& path, const ReportInput& in) {
    const std::filesystem::path page(path);
    const std::string folderName = page.stem().string() + "_images";
    ImageSink sink(in.embedImages ? std::filesystem::path() : page.parent_path() / folderName,
                   folderName);
    std::ostringstream o;
    writeHead(o, in);
    nlohmann::json lights = nlohmann::json::array();
    for (size_t li = 0; li < in.lights.size(); ++li) {
        lights.push_back(lightData(in, li));
        o << "<section class=\"light\" id=\"" << html(lightId(in, li)) << "\"><h2>Light "
          << html(in.lights[li]) << "</h2><div class=\"top\">";
        writeSummary(o, in, li);
        writeChartBox(o, in, li, lights.back());
        o << "</div>";
        writeContactTable(o, contactPairs(in, li));
        writeImages(o, in, li, sink);
        writeFlickerStrip(o, in, li, sink);
        writeSequenceChart(o, in, li);
        o << "</section>";
    }
    writeTail(o, in, lights);
    std::ofstream f(path);
    if (!f) throwInputError(path, "", "cannot be written");
    f << o.str();
}

}  // namespace so
