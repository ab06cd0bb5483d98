// The HTML report of a sweep (sweep_report.h; docs/sweep.md, "The report"). Every chart is drawn
// here as a table or inline SVG, so the page reads the same without script; the one small script
// only narrows the front charts to one artifact.
#include "raster_compare/compare/sweep_report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "raster_compare/compare/artifacts.h"
#include "raster_compare/compare/colour_scale.h"
#include "raster_compare/compare/contact_pairs.h"
#include "raster_compare/compare/html.h"
#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/tradeoff.h"

namespace so {

namespace {

std::string html(const std::string& s) {
    return htmlEscape(s);
}

// Four significant digits: enough to tell settings apart, short enough for a cell.
std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

// Full precision, for the data- attributes that tests and tools read instead of the text.
std::string exact(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

const std::string kMae = "mae";
const std::string kAcne = artifactClass(Artifact::Acne).metric;
const std::string kPeterPanning = artifactClass(Artifact::PeterPanning).metric;
const std::string kFrameMs = "cost.frame_ms";
const std::string kMemory = "cost.memory_bytes";

std::optional<double> metricOf(const SweepRow& r, const std::string& key) {
    const auto it = r.metrics.find(key);
    if (it == r.metrics.end()) return std::nullopt;
    return it->second;
}

// The metric's name for people, the metric table's label ("acne", "penumbra mae").
std::string metricName(const std::string& metric) {
    const MetricInfo* info = findMetric(metric);
    return info ? metricLabel(*info) : metric;
}

// "<b>acne</b> <code>acne_rate</code>": the name, and the key to look it up by in docs/metrics.md.
std::string metricTitle(const std::string& metric) {
    const std::string name = metricName(metric);
    return "<b>" + html(name) + "</b>" +
           (name == metric ? "" : " <code>" + html(metric) + "</code>");
}

// A cost axis: its metric, and from the metric table its name, the unit it is shown in and the
// factor to that unit.
struct Cost {
    std::string key, name, unit;
    double scale;
};

// Frame time and memory, then the work of a frame (docs/metrics.md, Work).
const std::vector<Cost>& costs() {
    static const std::vector<Cost> c = [] {
        std::vector<Cost> out;
        for (const char* key :
             {"cost.frame_ms", "cost.memory_bytes", "cost.work.fragments", "cost.work.texture_taps",
              "cost.work.texels_written", "cost.work.bytes_moved", "cost.work.draw_calls",
              "cost.work.passes", "cost.work.rays_traced"}) {
            const MetricInfo* m = findMetric(key);
            SO_CHECK(m != nullptr);
            out.push_back({key, metricLabel(*m), displayUnit(*m), displayScale(*m)});
        }
        return out;
    }();
    return c;
}

// ---- the rows grouped ----

// One section of the page: the rows of one light of one scene.
struct Group {
    std::string scene, light;
    std::vector<const SweepRow*> rows;
};

// In the order the rows first name them: the merge keeps the spec's order.
std::vector<Group> groupsOf(const SweepReportInput& in) {
    std::vector<Group> groups;
    for (const SweepRow& r : in.rows) {
        auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
            return g.scene == r.scene && g.light == r.light;
        });
        if (it == groups.end()) it = groups.insert(groups.end(), Group{r.scene, r.light, {}});
        it->rows.push_back(&r);
    }
    return groups;
}

std::vector<std::string> techniquesOf(const std::vector<const SweepRow*>& rows) {
    std::vector<std::string> names;
    for (const SweepRow* r : rows)
        if (std::find(names.begin(), names.end(), r->technique) == names.end())
            names.push_back(r->technique);
    return names;
}

std::vector<const SweepRow*> rowsOf(const Group& g, const std::string& technique) {
    std::vector<const SweepRow*> out;
    for (const SweepRow* r : g.rows)
        if (r->technique == technique) out.push_back(r);
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

// mae, then the artifacts in artifacts.h's order: those some row measured (null is "does not
// apply", e.g. penumbra_mae of a hard light).
std::vector<std::string> errorMetrics(const std::vector<const SweepRow*>& rows) {
    std::vector<std::string> out;
    if (anyHas(rows, kMae)) out.push_back(kMae);
    for (const ArtifactClass& c : kArtifactClasses)
        if (anyHas(rows, c.metric)) out.push_back(c.metric);
    return out;
}

// The setting without the technique's name, which its row or section already shows.
std::string shortLabel(const SweepRow& r) {
    const std::string prefix = r.technique + ":";
    if (r.label.compare(0, prefix.size(), prefix) == 0) return r.label.substr(prefix.size());
    return r.label == r.technique ? "(defaults)" : r.label;
}

// The swept values, "alpha=2, min=0.5": what a person changes in the spec.
// A swept parameter's value as the row's label writes it: a name for a parameter that picks a
// method ("denoiser=svgf", which `swept` holds as its index), else the number.
std::string sweptValue(const SweepRow& r, const std::string& name, double value) {
    const size_t colon = r.label.find(':');
    if (colon != std::string::npos) {
        const std::string settings = "," + r.label.substr(colon + 1) + ",";
        const size_t at = settings.find("," + name + "=");
        if (at != std::string::npos) {
            const size_t from = at + name.size() + 2;
            return settings.substr(from, settings.find(',', from) - from);
        }
    }
    return num(value);
}

std::string sweptName(const SweepRow& r) {
    if (r.swept.empty()) return shortLabel(r);
    std::string s;
    for (const auto& [name, value] : r.swept)
        s += (s.empty() ? "" : ", ") + name + "=" + sweptValue(r, name, value);
    return s;
}

// Okabe-Ito (colour-blind safe, as the artifact colours in artifacts.h), yellow last as it is
// faint on white; black is left to the front's line. Techniques take them in first-seen order,
// the same in every section.
using ColourMap = std::map<std::string, std::string>;

ColourMap techniqueColours(const SweepReportInput& in) {
    static const std::array<const char*, 8> palette = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                                       "#e69f00", "#56b4e9", "#999999", "#f0e442"};
    ColourMap colours;
    for (const SweepRow& r : in.rows)
        colours.emplace(r.technique, palette[colours.size() % palette.size()]);
    return colours;
}

// ---- Pareto fronts ----

// Settings as points of an error against a cost (in its shown unit), those that have both; `rows`
// runs beside `points`.
struct Points {
    std::vector<TradeoffPoint> points;
    std::vector<const SweepRow*> rows;
};

Points pointsOf(const std::vector<const SweepRow*>& rows, const std::string& metric,
                const Cost& cost) {
    Points p;
    for (const SweepRow* r : rows) {
        const std::optional<double> e = metricOf(*r, metric), c = metricOf(*r, cost.key);
        // A non-finite value has no place on an axis (and would stretch it without end).
        if (!e || !c || !std::isfinite(*e) || !std::isfinite(*c)) continue;
        p.points.push_back({r->label, r->technique, std::nullopt, *c * cost.scale, *e});
        p.rows.push_back(r);
    }
    return p;
}

// One axis of a chart: values onto the pixels [a, b]. Costs often span decades (a 512 map and an
// 8192 one differ 256 times in memory): more than 10x and the axis is logarithmic, or the cheap
// settings would all sit on one pixel.
struct Axis {
    double lo = 0.0, hi = 1.0, a = 0.0, b = 1.0;
    bool log = false;
    double at(double v) const {
        const double t =
            log ? std::log(std::max(v, lo) / lo) / std::log(hi / lo) : (v - lo) / (hi - lo);
        return a + t * (b - a);
    }
};

Axis axisOf(const std::vector<double>& values, double a, double b, bool mayBeLog) {
    Axis x;
    x.a = a;
    x.b = b;
    const auto [mn, mx] = std::minmax_element(values.begin(), values.end());
    x.log = mayBeLog && *mn > 0.0 && *mx / *mn > 10.0;
    // A linear axis starts at 0, so a front's drop reads as a share of the error.
    x.lo = x.log ? *mn : std::min(0.0, *mn);
    x.hi = *mx > x.lo ? *mx : x.lo + 1.0;
    return x;
}

// Ticks a person reads at a glance: 1, 2 and 5 times a power of ten, within the axis; on a log
// axis spanning many decades, the powers of ten alone.
std::vector<double> ticksOf(const Axis& x) {
    std::vector<double> ticks;
    const auto inside = [&](double v) { return v >= x.lo * (1 - 1e-9) && v <= x.hi * (1 + 1e-9); };
    if (x.log) {
        for (double decade = std::pow(10.0, std::floor(std::log10(x.lo))); decade <= x.hi;
             decade *= 10.0)
            for (double m : {1.0, 2.0, 5.0})
                if (inside(m * decade)) ticks.push_back(m * decade);
        if (ticks.size() > 7)
            ticks.erase(std::remove_if(ticks.begin(), ticks.end(),
                                       [](double v) {
                                           const double l = std::log10(v);
                                           return std::fabs(l - std::round(l)) > 1e-9;
                                       }),
                        ticks.end());
        return ticks;
    }
    const double raw = (x.hi - x.lo) / 4.0, p = std::pow(10.0, std::floor(std::log10(raw)));
    const double step = raw / p < 1.5 ? p : raw / p < 3.5 ? 2 * p : raw / p < 7.5 ? 5 * p : 10 * p;
    // Multiples of the step counted as integers, so 0.1 + 0.2 cannot print as 0.30000000000000004.
    for (double k = std::ceil(x.lo / step - 1e-9); k * step <= x.hi + step * 1e-9; k += 1.0)
        ticks.push_back(k * step + 0.0);  // + 0.0: a -0 tick prints as "0"
    return ticks;
}

constexpr double kChartW = 420, kChartH = 260, kLeft = 60, kRight = 14, kTop = 12, kBottom = 42;

std::string axesSvg(const Axis& x, const Axis& y, const std::string& xTitle,
                    const std::string& yTitle) {
    std::ostringstream s;
    s << "<g class=\"axes\"><line x1=\"" << kLeft << "\" y1=\"" << kChartH - kBottom << "\" x2=\""
      << kChartW - kRight << "\" y2=\"" << kChartH - kBottom << "\"/><line x1=\"" << kLeft
      << "\" y1=\"" << kTop << "\" x2=\"" << kLeft << "\" y2=\"" << kChartH - kBottom << "\"/>";
    for (double v : ticksOf(x))
        s << "<text x=\"" << x.at(v) << "\" y=\"" << kChartH - kBottom + 14
          << "\" text-anchor=\"middle\">" << num(v) << "</text>";
    for (double v : ticksOf(y))
        s << "<text x=\"" << kLeft - 4 << "\" y=\"" << y.at(v) + 4 << "\" text-anchor=\"end\">"
          << num(v) << "</text><line class=\"grid\" x1=\"" << kLeft + 1 << "\" y1=\"" << y.at(v)
          << "\" x2=\"" << kChartW - kRight << "\" y2=\"" << y.at(v) << "\"/>";
    s << "<text x=\"" << (kLeft + kChartW - kRight) / 2 << "\" y=\"" << kChartH - 6
      << "\" text-anchor=\"middle\">" << html(xTitle) << (x.log ? ", log scale" : "")
      << "</text><text transform=\"translate(12," << (kTop + kChartH - kBottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << html(yTitle) << "</text></g>";
    return s.str();
}

std::string pointSvg(const Points& p, size_t i, double cx, double cy, const std::string& colour,
                     bool onFront, const Cost& cost) {
    std::ostringstream s;
    s << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"" << (onFront ? 4.5 : 3)
      << "\" fill=\"" << colour << "\""
      << (onFront ? " stroke=\"#000\" stroke-width=\"1.3\"" : " fill-opacity=\"0.45\"")
      << "><title>" << html(p.points[i].label) << ": " << num(p.points[i].cost) << " " << cost.unit
      << ", error " << num(p.points[i].error) << "</title></circle>";
    return s.str();
}

// Every setting in its technique's colour, faint; the front joined by a line, its points ringed.
std::string frontSvg(const Points& p, const std::vector<size_t>& front, const Cost& cost,
                     const std::string& metric, const ColourMap& colours) {
    std::vector<double> xs, ys;
    for (const TradeoffPoint& q : p.points) {
        xs.push_back(q.cost);
        ys.push_back(q.error);
    }
    const Axis x = axisOf(xs, kLeft + 6, kChartW - kRight - 6, true);
    const Axis y = axisOf(ys, kChartH - kBottom - 4, kTop + 4, false);
    std::ostringstream s;
    s << "<svg class=\"front-chart\" viewBox=\"0 0 " << kChartW << " " << kChartH << "\" width=\""
      << kChartW << "\" height=\"" << kChartH << "\" role=\"img\" aria-label=\""
      << html(metric + " against " + cost.name) << "\">"
      << axesSvg(x, y, cost.name + " (" + cost.unit + ")", metric);
    for (size_t i = 0; i < p.points.size(); ++i)
        if (std::find(front.begin(), front.end(), i) == front.end())
            s << pointSvg(p, i, x.at(xs[i]), y.at(ys[i]), colours.at(p.rows[i]->technique), false,
                          cost);
    s << "<polyline class=\"front\" points=\"";
    for (size_t i : front) s << x.at(xs[i]) << "," << y.at(ys[i]) << " ";
    s << "\"/>";
    for (size_t i : front)
        s << pointSvg(p, i, x.at(xs[i]), y.at(ys[i]), colours.at(p.rows[i]->technique), true, cost);
    s << "</svg>";
    return s.str();
}

std::string frontTable(const Points& p, const std::vector<size_t>& front, const Cost& cost,
                       const std::string& metric) {
    std::ostringstream s;
    s << "<table class=\"front\" data-metric=\"" << html(metric) << "\" data-cost=\""
      << html(cost.key) << "\"><thead><tr><th class=\"text\">setting on the front</th><th>"
      << html(cost.name) << " (" << cost.unit << ")</th><th>" << html(metric)
      << "</th></tr></thead><tbody>";
    for (size_t i : front)
        s << "<tr><td class=\"text label\">" << html(p.points[i].label) << "</td><td data-v=\""
          << exact(p.points[i].cost) << "\">" << num(p.points[i].cost) << "</td><td data-v=\""
          << exact(p.points[i].error) << "\">" << num(p.points[i].error) << "</td></tr>";
    s << "</tbody></table>";
    return s.str();
}

// The metrics a front is drawn for: mae, and the artifacts that some setting shows (a front of
// zeros says nothing but "all settings are free of it", which the note under the charts says).
std::vector<std::string> frontMetrics(const Group& g) {
    std::vector<std::string> out;
    for (const std::string& m : errorMetrics(g.rows))
        if (m == kMae || anyNonZero(g.rows, m)) out.push_back(m);
    return out;
}

std::string techniqueLegend(const Group& g, const ColourMap& colours) {
    std::ostringstream s;
    s << "<div class=\"legend\">";
    for (const std::string& t : techniquesOf(g.rows))
        s << "<span><i style=\"background:" << colours.at(t) << "\"></i>" << html(t) << "</span>";
    s << "<span>ringed and joined: the Pareto front</span></div>";
    return s.str();
}

// One chart and its table, or "" when no setting has both the error and the cost.
std::string frontCard(const Group& g, const std::string& metric, const Cost& cost,
                      const ColourMap& colours) {
    const Points p = pointsOf(g.rows, metric, cost);
    if (p.points.empty()) return "";
    const std::vector<size_t> front = paretoFront(p.points);
    return "<figure class=\"front-card\" data-metric=\"" + html(metric) + "\" data-cost=\"" +
           html(cost.key) + "\"><figcaption>" + metricTitle(metric) + " against " +
           html(cost.name) + "</figcaption>" + frontSvg(p, front, cost, metric, colours) +
           frontTable(p, front, cost, metric) + "</figure>";
}

// Without script every chart shows; with it, the boxes (mae first; frame time and memory first)
// narrow them to one artifact and to some costs.
void writeFrontsIntro(std::ostream& o, const std::vector<std::string>& metrics,
                      const SweepReportInput& in) {
    o << "<h3>Pareto fronts: error against cost</h3><p class=\"muted\">A setting is on the front "
         "when no other is both cheaper and more accurate. Times were measured on <b>"
      << html(in.timedOn.empty() ? "an unrecorded renderer" : in.timedOn)
      << "</b>; memory is the GL memory the technique holds for the light; the work of a frame "
         "(fragments, texture taps, texels written, bytes moved, draw calls, passes) is counted "
         "exactly, what a GPU's time follows (docs/metrics.md, Work).</p>"
      << "<label class=\"js-only\" hidden>artifact <select class=\"front-select\">";
    for (const std::string& m : metrics)
        o << "<option value=\"" << html(m) << "\"" << (m == kMae ? " selected" : "") << ">"
          << html(metricName(m)) << "</option>";
    o << "<option value=\"*\">all</option></select></label> <label class=\"js-only\" "
         "hidden>cost <select class=\"cost-select\"><option value=\""
      << kFrameMs << " " << kMemory << "\" selected>frame time and memory</option>";
    for (const Cost& c : costs())
        if (c.key != kFrameMs && c.key != kMemory)
            o << "<option value=\"" << html(c.key) << "\">" << html(c.name) << "</option>";
    o << "<option value=\"*\">all</option></select></label>";
}

void writeFronts(std::ostream& o, const Group& g, const SweepReportInput& in,
                 const ColourMap& colours) {
    const std::vector<std::string> metrics = frontMetrics(g);
    writeFrontsIntro(o, metrics, in);
    std::string cards;
    for (const std::string& m : metrics)
        for (const Cost& cost : costs()) cards += frontCard(g, m, cost, colours);
    if (cards.empty())
        o << "<p class=\"muted\">No setting has both an error and a cost to draw.</p>";
    else
        o << techniqueLegend(g, colours) << "<div class=\"fronts\">" << cards << "</div>";
    std::string zero;
    for (const std::string& m : errorMetrics(g.rows))
        if (std::find(metrics.begin(), metrics.end(), m) == metrics.end())
            zero += (zero.empty() ? "" : ", ") + metricName(m);
    if (!zero.empty())
        o << "<p class=\"muted\">No chart for " << html(zero) << ": zero in every setting.</p>";
}

// ---- the cheapest setting at error budgets ----

// By the cost, then memory (frame time, for memory itself): cheapestWithin() keeps the first of
// equal costs, so this order breaks the ties. Settings without the cost cannot be ranked and are
// left out.
std::vector<const SweepRow*> byCost(std::vector<const SweepRow*> rows, const Cost& cost) {
    rows.erase(std::remove_if(rows.begin(), rows.end(),
                              [&](const SweepRow* r) { return !metricOf(*r, cost.key); }),
               rows.end());
    const std::string& tieKey = cost.key == kMemory ? kFrameMs : kMemory;
    const auto tie = [&](const SweepRow* r) { return metricOf(*r, tieKey).value_or(HUGE_VAL); };
    std::stable_sort(rows.begin(), rows.end(), [&](const SweepRow* a, const SweepRow* b) {
        const double ca = *metricOf(*a, cost.key), cb = *metricOf(*b, cost.key);
        return ca < cb || (ca == cb && tie(a) < tie(b));
    });
    return rows;
}

std::string budgetRow(const std::vector<const SweepRow*>& ranked, const std::string& metric,
                      const std::vector<double>& budgets, const Cost& cost) {
    const Points p = pointsOf(ranked, metric, cost);
    std::ostringstream s;
    for (double budget : budgets) {
        const std::optional<size_t> best = cheapestWithin(p.points, budget);
        if (!best) {
            s << "<td class=\"text none\">none</td>";
            continue;
        }
        s << "<td class=\"text\" title=\"" << html(p.points[*best].label) << "\">"
          << html(shortLabel(*p.rows[*best])) << " <span class=\"muted\">"
          << num(p.points[*best].cost) << " " << cost.unit << "</span></td>";
    }
    return s.str();
}

void writeBudgetTable(std::ostream& o, const Group& g, const std::vector<double>& budgets,
                      const Cost& cost) {
    o << "<div class=\"budget-box\" data-cost=\"" << html(cost.key) << "\"><p class=\"caption\">By "
      << html(cost.name)
      << ":</p><table class=\"budgets\"><thead><tr><th "
         "class=\"text\">technique</th><th class=\"text\">error</th>";
    for (double b : budgets) o << "<th class=\"text\">&le; " << num(b) << "</th>";
    o << "</tr></thead><tbody>";
    for (const std::string& t : techniquesOf(g.rows)) {
        const std::vector<const SweepRow*> ranked = byCost(rowsOf(g, t), cost);
        bool first = true;
        for (const std::string& m : errorMetrics(ranked)) {
            o << "<tr" << (first ? " class=\"first\"" : "") << " data-technique=\"" << html(t)
              << "\" data-metric=\"" << html(m) << "\"><th class=\"text\">"
              << (first ? html(t) : "") << "</th><td class=\"text\">" << html(metricName(m))
              << "</td>" << budgetRow(ranked, m, budgets, cost) << "</tr>";
            first = false;
        }
    }
    o << "</tbody></table></div>";
}

// One table per cost, frame time's first and the others hidden until the cost box names them.
void writeBudgets(std::ostream& o, const Group& g, const std::vector<double>& budgets) {
    o << "<h3>Cheapest setting per technique at error budgets</h3><p class=\"muted\">The setting "
         "with the least cost (frame time by default, ties: the least memory) whose error is at "
         "most the budget; \"none\" when no setting of the technique is that accurate.</p>";
    for (const Cost& cost : costs())
        if (anyHas(g.rows, cost.key)) writeBudgetTable(o, g, budgets, cost);
}

// ---- heat maps over the swept parameters ----

// A technique's settings over its one or two swept parameters: each parameter's sorted unique
// values, and the setting at each combination (the first, should the merge give two).
struct Grid {
    std::vector<std::string> params;
    std::vector<std::vector<double>> values;
    std::map<std::vector<double>, const SweepRow*> at;
};

std::optional<Grid> gridOf(const std::vector<const SweepRow*>& rows) {
    if (rows.empty()) return std::nullopt;
    Grid g;
    for (const auto& [name, value] : rows.front()->swept) g.params.push_back(name);
    if (g.params.empty() || g.params.size() > 2) return std::nullopt;
    std::vector<std::set<double>> values(g.params.size());
    for (const SweepRow* r : rows) {
        if (r->swept.size() != g.params.size()) return std::nullopt;
        std::vector<double> key;
        for (size_t k = 0; k < g.params.size(); ++k) {
            if (r->swept[k].first != g.params[k]) return std::nullopt;
            key.push_back(r->swept[k].second);
            values[k].insert(r->swept[k].second);
        }
        g.at.emplace(key, r);
    }
    for (const std::set<double>& v : values) g.values.emplace_back(v.begin(), v.end());
    return g;
}

// "background:#rrggbb;color:#fff": the cell's colour and a text colour that keeps it legible.
std::string cellStyle(const Rgb& c) {
    return "background:" + hexColour(c) + ";color:" + textColour(c);
}

std::string scaleLegend(const ColourScale& s, bool acne) {
    std::ostringstream o;
    o << "<div class=\"legend\"><span>" << num(s.lo) << "</span><span class=\"ramp\" "
      << "style=\"background:" << rampGradient() << "\"></span><span>" << num(s.hi)
      << "</span><span class=\"muted\">"
      << (s.log ? "log scale (0 takes the lowest colour)" : "linear scale")
      << "; &#9733; the lowest" << (acne ? "; &#10003; no acne (exactly 0)" : "")
      << "</span></div>";
    return o.str();
}

// One cell: the value printed on its colour; &#9733; on the lowest, &#10003; on acne-free cells.
std::string heatCell(const SweepRow* r, const std::string& metric, const ColourScale& scale,
                     double lowest) {
    const std::optional<double> v = r ? metricOf(*r, metric) : std::nullopt;
    if (!v) return "<td class=\"na\">&ndash;</td>";
    const bool best = *v == lowest, clean = metric == kAcne && *v == 0.0;
    std::string cls = std::string(best ? " best" : "") + (clean ? " clean" : "");
    return "<td class=\"cell" + cls + "\" data-v=\"" + exact(*v) + "\" style=\"" +
           cellStyle(rampColour(scalePosition(scale, *v))) + "\" title=\"" + html(r->label) +
           "\">" + (best ? "&#9733; " : "") + (clean ? "&#10003; " : "") + num(*v) + "</td>";
}

std::vector<double> gridValues(const Grid& g, const std::string& metric) {
    std::vector<double> values;
    for (const auto& [key, r] : g.at)
        if (const std::optional<double> v = metricOf(*r, metric)) values.push_back(*v);
    return values;
}

const SweepRow* cellAt(const Grid& g, std::vector<double> key) {
    const auto it = g.at.find(key);
    return it == g.at.end() ? nullptr : it->second;
}

// Axis k's value v as the labels write it (sweptValue), from any row that has it.
std::string axisText(const Grid& g, size_t k, double v) {
    for (const auto& [key, r] : g.at)
        if (key[k] == v) return sweptValue(*r, g.params[k], v);
    return num(v);
}

// Two parameters: the first down, the second across, one metric's values as colours.
std::string heatMap(const Grid& g, const std::string& technique, const std::string& metric) {
    const std::vector<double> values = gridValues(g, metric);
    if (values.empty()) return "";
    const ColourScale scale = scaleOf(values);
    const double lowest = *std::min_element(values.begin(), values.end());
    std::ostringstream o;
    o << "<figure class=\"heat-card\"><figcaption>" << metricTitle(metric)
      << "</figcaption><table class=\"heat\" data-technique=\"" << html(technique)
      << "\" data-metric=\"" << html(metric) << "\"><thead><tr><th "
      << "class=\"corner\">" << html(g.params[0]) << " &darr; " << html(g.params[1])
      << " &rarr;</th>";
    for (double b : g.values[1]) o << "<th>" << html(axisText(g, 1, b)) << "</th>";
    o << "</tr></thead><tbody>";
    for (double a : g.values[0]) {
        o << "<tr><th>" << html(axisText(g, 0, a)) << "</th>";
        for (double b : g.values[1]) o << heatCell(cellAt(g, {a, b}), metric, scale, lowest);
        o << "</tr>";
    }
    o << "</tbody></table>" << scaleLegend(scale, metric == kAcne) << "</figure>";
    return o.str();
}

// One parameter: a row per value, a column per metric, each column on its own colour scale.
std::string sweepTable(const Grid& g, const std::string& technique,
                       const std::vector<std::string>& metrics) {
    std::ostringstream o;
    o << "<table class=\"heat one\" data-technique=\"" << html(technique) << "\"><thead><tr><th "
      << "class=\"corner\">" << html(g.params[0]) << "</th>";
    for (const std::string& m : metrics) o << "<th>" << html(metricName(m)) << "</th>";
    o << "</tr></thead><tbody>";
    for (double a : g.values[0]) {
        o << "<tr><th>" << html(axisText(g, 0, a)) << "</th>";
        for (const std::string& m : metrics) {
            const std::vector<double> values = gridValues(g, m);
            const double lowest =
                values.empty() ? 0.0 : *std::min_element(values.begin(), values.end());
            o << heatCell(cellAt(g, {a}), m, scaleOf(values), lowest);
        }
        o << "</tr>";
    }
    o << "</tbody></table><p class=\"muted\">Each column on its own colour scale, dark the lowest; "
         "&#9733; the lowest, &#10003; no acne.</p>";
    return o.str();
}

// Among the settings with acne_rate exactly 0 (a share of pixels: 0 is not one pixel of acne),
// the one with the least peter-panning (ties: the first in the rows' order, the spec's: the
// smallest values of the grid, not the one a noisy frame time favours); a sentence, or "" when the
// technique has no acne measured.
std::string noAcneVerdict(const std::string& technique, const std::vector<const SweepRow*>& rows) {
    const SweepRow* best = nullptr;
    const auto better = [](const SweepRow* a, const SweepRow* b) {
        return metricOf(*a, kPeterPanning).value_or(HUGE_VAL) <
               metricOf(*b, kPeterPanning).value_or(HUGE_VAL);
    };
    bool measured = false;
    for (const SweepRow* r : rows) {
        const std::optional<double> acne = metricOf(*r, kAcne);
        measured |= acne.has_value();
        if (acne && *acne == 0.0 && (!best || better(r, best))) best = r;
    }
    if (!measured) return "";
    std::string s = technique + ": ";
    if (!best) return s + "every setting has acne";
    const std::optional<double> pp = metricOf(*best, kPeterPanning);
    return s + sweptName(*best) + " has no acne and the least peter-panning (" +
           (pp ? num(*pp) : "not measured") + ")";
}

// The techniques of the section that sweep at least one parameter, with their rows.
std::vector<std::pair<std::string, std::vector<const SweepRow*>>> sweptTechniques(const Group& g) {
    std::vector<std::pair<std::string, std::vector<const SweepRow*>>> out;
    for (const std::string& t : techniquesOf(g.rows)) {
        std::vector<const SweepRow*> rows = rowsOf(g, t);
        if (rows.size() > 1 && !rows.front()->swept.empty()) out.emplace_back(t, std::move(rows));
    }
    return out;
}

void writeVerdicts(std::ostream& o, const Group& g) {
    std::ostringstream items;
    for (const auto& [t, rows] : sweptTechniques(g))
        if (const std::string v = noAcneVerdict(t, rows); !v.empty())
            items << "<li class=\"verdict\" data-technique=\"" << html(t) << "\">" << html(v)
                  << "</li>";
    if (items.tellp() > 0)
        o << "<p class=\"muted\">No acne and the least peter-panning, per swept technique:</p><ul "
             "class=\"verdicts\">"
          << items.str() << "</ul>";
}

void writeHeatMaps(std::ostream& o, const Group& g) {
    std::ostringstream maps;
    for (const auto& [t, rows] : sweptTechniques(g)) {
        const std::optional<Grid> grid = gridOf(rows);
        if (!grid) continue;
        std::vector<std::string> metrics;
        for (const std::string& m : {kAcne, kPeterPanning, kMae})
            if (anyHas(rows, m)) metrics.push_back(m);
        if (metrics.empty()) continue;
        maps << "<h4>" << html(t) << " over " << html(grid->params[0])
             << (grid->params.size() == 2 ? " &times; " + html(grid->params[1]) : "") << "</h4>";
        if (grid->params.size() == 1) {
            maps << sweepTable(*grid, t, metrics);
            continue;
        }
        maps << "<div class=\"heats\">";
        for (const std::string& m : metrics) maps << heatMap(*grid, t, m);
        maps << "</div>";
    }
    if (maps.tellp() > 0) o << "<h3>Over the swept parameters</h3>" << maps.str();
}

// ---- the page ----

constexpr const char* kStyle = R"(<style>
body{font-family:system-ui,sans-serif;margin:1.5em;color:#222}
h1{font-size:1.4em}h2{font-size:1.2em;margin-top:2em;border-top:1px solid #ccc;padding-top:.6em}
h3{font-size:1.05em;margin-top:1.4em}h4{font-size:.95em;margin:1em 0 .3em}
.muted{color:#666;font-size:.9em}
table{border-collapse:collapse;font-size:12px}
th,td{padding:2px 6px;text-align:right;font-variant-numeric:tabular-nums}
.text{text-align:left}
table.front td,table.budgets td,table.budgets th,table.failed td,table.failed th,
table.provenance td,table.provenance th{border-bottom:1px solid #e4e4e4}
table.budgets tr.first th,table.budgets tr.first td{border-top:2px solid #999}
table.budgets td.none{color:#999}
.fronts,.heats{display:flex;flex-wrap:wrap;gap:1em}
figure{margin:0;border:1px solid #ddd;padding:.5em}
figcaption{font-size:.9em;margin-bottom:.3em}
svg.front-chart{font-size:10px;display:block}
svg .axes line{stroke:#444}svg .axes line.grid{stroke:#eee}
svg polyline.front{fill:none;stroke:#000;stroke-width:1.5}
.legend{display:flex;flex-wrap:wrap;align-items:center;gap:.8em;font-size:12px;margin:.4em 0}
.legend i{display:inline-block;width:10px;height:10px;margin-right:3px;border-radius:50%}
.legend .ramp{display:inline-block;width:160px;height:12px;border:1px solid #999}
table.heat td,table.heat th{border:1px solid #fff;padding:4px 8px}
table.heat thead th,table.heat tbody th{background:#eee}
table.heat td.best{font-weight:bold}
table.heat td.clean{outline:2px dashed #e00;outline-offset:-3px}
table.heat td.na{background:#f4f4f4;color:#999}
.failed-box{border:2px solid #c00;background:#fff0f0;padding:.6em 1em;margin:1em 0}
.failed-box h2{color:#a00;border:0;margin:0 0 .4em;padding:0}
ul.verdicts{margin:.3em 0}
nav ol{columns:2;font-size:.95em}
</style>)";

// With script, the select box narrows the front charts to one artifact (mae first); without it,
// every chart shows.
constexpr const char* kScript = R"(<script>
document.querySelectorAll('select.front-select').forEach(function (s) {
  var section = s.closest('section'), cost = section.querySelector('select.cost-select');
  s.parentNode.hidden = false;
  cost.parentNode.hidden = false;
  function apply() {
    var costs = cost.value.split(' ');
    section.querySelectorAll('.front-card').forEach(function (c) {
      c.hidden = (s.value !== '*' && c.dataset.metric !== s.value) ||
                 (cost.value !== '*' && costs.indexOf(c.dataset.cost) < 0);
    });
    // The budget tables of the first cost named (frame time for "frame time and memory").
    section.querySelectorAll('.budget-box').forEach(function (b) {
      b.hidden = cost.value !== '*' && b.dataset.cost !== costs[0];
    });
  }
  s.addEventListener('change', apply);
  cost.addEventListener('change', apply);
  apply();
});
</script>)";

std::string groupId(size_t gi) {
    return "light-" + std::to_string(gi);
}

size_t finishedTasks(const SweepReportInput& in) {
    std::set<std::string> ids;
    for (const SweepRow& r : in.rows) ids.insert(r.task);
    return ids.size();
}

void writeFailed(std::ostream& o, const SweepReportInput& in) {
    if (in.failed.empty()) return;
    o << "<div class=\"failed-box\" id=\"failed\"><h2>" << in.failed.size() << " task"
      << (in.failed.size() == 1 ? "" : "s")
      << " failed</h2><table class=\"failed\"><thead><tr><th class=\"text\">task</th><th "
         "class=\"text\">scene</th><th class=\"text\">setting</th><th "
         "class=\"text\">reason</th><th class=\"text\">log</th></tr></thead><tbody>";
    for (const SweepFailure& f : in.failed) {
        o << "<tr><td class=\"text\"><code>" << html(f.task) << "</code></td><td class=\"text\">"
          << html(f.scene) << "</td><td class=\"text\">" << html(f.label)
          << "</td><td class=\"text\">" << html(f.reason) << "</td><td class=\"text\">";
        if (!f.log.empty())
            o << "<a href=\"" << html(urlEncode(f.log, "/")) << "\">" << html(f.log) << "</a>";
        o << "</td></tr>";
    }
    o << "</tbody></table></div>";
}

void writeHead(std::ostream& o, const SweepReportInput& in, const std::vector<Group>& groups) {
    o << "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadow-oracle "
         "sweep: "
      << html(in.sweepName) << "</title>" << kStyle << "</head><body><h1>Sweep "
      << html(in.sweepName) << "</h1><p>Spec <code>" << html(in.specFile) << "</code>. <b>"
      << finishedTasks(in) << " of " << in.tasks << " tasks finished</b>"
      << (in.failed.empty() ? "" : ", " + std::to_string(in.failed.size()) + " failed") << ", "
      << in.rows.size() << " setting results. Times were measured on <b>"
      << html(in.timedOn.empty() ? "an unrecorded renderer" : in.timedOn) << "</b>.";
    if (in.timedOn.find("llvmpipe") != std::string::npos)
        o << " (Mesa's CPU rasterizer: its times rank the settings on this machine, not on a "
             "GPU.)";
    o << "</p>";
    writeFailed(o, in);
    o << "<nav><b>Contents</b><ol>";
    for (size_t gi = 0; gi < groups.size(); ++gi)
        o << "<li><a href=\"#" << groupId(gi) << "\">" << html(groups[gi].scene) << " &mdash; "
          << html(groups[gi].light) << "</a></li>";
    o << "<li><a href=\"#provenance\">provenance</a></li></ol></nav>";
}

void writeGroup(std::ostream& o, const Group& g, size_t gi, const SweepReportInput& in,
                const ColourMap& colours) {
    o << "<section id=\"" << groupId(gi) << "\"><h2>" << html(g.scene) << " &mdash; light "
      << html(g.light) << "</h2><p class=\"muted\">" << g.rows.size() << " settings of "
      << techniquesOf(g.rows).size() << " techniques.</p>";
    writeVerdicts(o, g);
    std::vector<ContactSetting> settings;
    for (const SweepRow* r : g.rows)
        settings.push_back({r->label, r->technique, r->parameters, contactRatesOf(r->metrics)});
    writeContactTable(o, pairContactSettings(settings));
    writeFronts(o, g, in, colours);
    writeBudgets(o, g, in.errorBudgets);
    writeHeatMaps(o, g);
    o << "</section>\n";
}

void writeTail(std::ostream& o, const SweepReportInput& in) {
    o << "<h2 id=\"provenance\">Provenance</h2><table class=\"provenance\">";
    for (const auto& [key, value] : in.provenance)
        o << "<tr><th class=\"text\">" << html(key) << "</th><td class=\"text\">" << html(value)
          << "</td></tr>";
    o << "</table>" << kScript << "</body></html>\n";
}

}  // namespace

void writeSweepReport(const std::string& path, const SweepReportInput& in) {
    const std::vector<Group> groups = groupsOf(in);
    const ColourMap colours = techniqueColours(in);
    std::ostringstream o;
    writeHead(o, in, groups);
    for (size_t gi = 0; gi < groups.size(); ++gi) writeGroup(o, groups[gi], gi, in, colours);
    writeTail(o, in);
    std::ofstream f(path);
    if (!f) throwInputError(path, "", "cannot be written");
    f << o.str();
    if (!f) throwInputError(path, "", "cannot be written");
}

}  // namespace so
