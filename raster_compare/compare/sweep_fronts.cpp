// The sweep report's Pareto fronts of each artifact's error against each cost, drawn as inline
// SVG beside a table, and the cheapest setting per technique at error budgets (sweep_sections.h).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "raster_compare/compare/html.h"
#include "raster_compare/compare/result_row.h"
#include "raster_compare/compare/sweep_sections.h"
#include "raster_compare/compare/tradeoff.h"

namespace so::sweep {

namespace {

const std::string kFrameMs = "cost.frame_ms";
const std::string kMemory = "cost.memory_bytes";

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
        p.points.push_back(
            {r->result.label, r->result.technique, std::nullopt, *c * cost.scale, *e});
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
            s << pointSvg(p, i, x.at(xs[i]), y.at(ys[i]), colours.at(p.rows[i]->result.technique),
                          false, cost);
    s << "<polyline class=\"front\" points=\"";
    for (size_t i : front) s << x.at(xs[i]) << "," << y.at(ys[i]) << " ";
    s << "\"/>";
    for (size_t i : front)
        s << pointSvg(p, i, x.at(xs[i]), y.at(ys[i]), colours.at(p.rows[i]->result.technique), true,
                      cost);
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
        s << "<tr><td class=\"text label\">" << html(p.points[i].label)
          << fidelityMark(p.rows[i]->result.fidelity, p.rows[i]->result.provenanceText)
          << "</td><td data-v=\"" << exact(p.points[i].cost) << "\">" << num(p.points[i].cost)
          << "</td><td data-v=\"" << exact(p.points[i].error) << "\">" << num(p.points[i].error)
          << "</td></tr>";
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

}  // namespace

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

namespace {

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
    for (const std::optional<size_t>& best : cheapestAtBudgets(p.points, budgets)) {
        if (!best) {
            s << "<td class=\"text none\">none</td>";
            continue;
        }
        s << "<td class=\"text\" title=\"" << html(p.points[*best].label) << "\">"
          << html(shortLabel(*p.rows[*best]))
          << fidelityMark(p.rows[*best]->result.fidelity, p.rows[*best]->result.provenanceText)
          << " <span class=\"muted\">" << num(p.points[*best].cost) << " " << cost.unit
          << "</span></td>";
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

}  // namespace

// One table per cost, frame time's first and the others hidden until the cost box names them.
void writeBudgets(std::ostream& o, const Group& g, const std::vector<double>& budgets) {
    o << "<h3>Cheapest setting per technique at error budgets</h3><p class=\"muted\">The setting "
         "with the least cost (frame time by default, ties: the least memory) whose error is at "
         "most the budget; \"none\" when no setting of the technique is that accurate.</p>";
    for (const Cost& cost : costs())
        if (anyHas(g.rows, cost.key)) writeBudgetTable(o, g, budgets, cost);
}

}  // namespace so::sweep
