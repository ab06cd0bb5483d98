// The sweep report's heat maps over a technique's one or two swept parameters, coloured by acne,
// peter-panning and mae, and its "no acne, least peter-panning" verdicts (sweep_sections.h).
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "raster_compare/compare/colour_scale.h"
#include "raster_compare/compare/result_row.h"
#include "raster_compare/compare/sweep_sections.h"

namespace so::sweep {

namespace {

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
            key.push_back(r->swept[k].second.number);
            values[k].insert(r->swept[k].second.number);
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
           cellStyle(rampColour(scalePosition(scale, *v))) + "\" title=\"" + html(r->result.label) +
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

// Axis k's value v as the labels write it (a method's name, "svgf"), from any row that has it.
std::string axisText(const Grid& g, size_t k, double v) {
    for (const auto& [key, r] : g.at)
        if (key[k] == v) return r->swept[k].second.text();
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

}  // namespace

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

}  // namespace so::sweep
