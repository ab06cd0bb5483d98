#include "raster_compare/compare/index_page.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"
#include "raster_compare/compare/colour_scale.h"
#include "raster_compare/compare/html.h"
#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/metrics.h"

namespace so {

using nlohmann::json;

namespace {

// ---- metrics.json -> structs ----

std::string optionalString(const json& object, const std::string& key, const JsonReader& r,
                           const std::string& field) {
    const json* v = JsonReader::find(object, key);
    if (!v || v->is_null()) return "";
    return r.string(*v, field + "." + key);
}

// ---- the page ----

// A matrix: its metric (name as in metrics.csv, which way is better, its meaning) and its title.
struct MetricSpec {
    const MetricInfo* metric;
    const char* title;
};

const std::vector<MetricSpec>& metricSpecs() {
    static const std::vector<MetricSpec> specs = {
        {&metricInfo("mae"), "Mean absolute error"},
        {&metricInfo("acne_rate"), "Shadow acne"},
        {&metricInfo("peter_panning_rate"), "Peter-panning"},
        {&metricInfo("boundary_displacement_px.p95"), "Shadow boundary displacement (p95, pixels)"},
        {&metricInfo("light_bleeding_rate"), "Light bleeding"},
        {&metricInfo("penumbra_mae"), "Penumbra error"},
        {&metricInfo("sequence.mae_mean"), "Error over a sequence (mean of its frames)"},
        {&metricInfo("sequence.lag_mae"), "Lag and ghosting in a sequence"},
    };
    return specs;
}

std::string html(const std::string& s) {
    return htmlEscape(s);
}

std::string lightHref(const std::string& report, const std::string& light) {
    return urlEncode(report, "/") + "#light-" + urlEncode(light, "");
}

// Three significant digits, but whole numbers from 1000 up: "1.42e+03 ms" reads badly in a cell.
std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, std::fabs(v) >= 1000.0 ? "%.0f" : "%.3g", v);
    return buf;
}

// The grid shared by every matrix: rows are the technique labels of all runs in first-seen
// order, columns every (run, light).
struct Column {
    size_t entry;
    std::string light;
    bool firstOfScene;  // drawn with a rule on its left, so the scenes stand apart
};

struct Grid {
    std::vector<std::string> rows;
    std::vector<Column> columns;
    // [entry][label]: that run's result of the label (a run may lack a label: no cell).
    std::vector<std::map<std::string, const ResultRow*>> byLabel;
};

Grid gridOf(const std::vector<IndexEntry>& entries) {
    Grid g;
    for (size_t e = 0; e < entries.size(); ++e) {
        g.byLabel.emplace_back();
        for (const ResultRow& r : entries[e].metrics.results) {
            if (!g.byLabel[e].emplace(r.label, &r).second) continue;  // the first one counts
            if (std::find(g.rows.begin(), g.rows.end(), r.label) == g.rows.end())
                g.rows.push_back(r.label);
        }
        for (const std::string& light : entries[e].metrics.lights)
            g.columns.push_back({e, light, light == entries[e].metrics.lights.front()});
    }
    return g;
}

const LightRow* cellOf(const Grid& g, const std::string& row, const Column& c) {
    const auto it = g.byLabel[c.entry].find(row);
    return it == g.byLabel[c.entry].end() ? nullptr : it->second->light(c.light);
}

std::vector<double> valuesOf(const Grid& g, const MetricSpec& spec) {
    std::vector<double> values;
    for (const std::string& row : g.rows)
        for (const Column& c : g.columns)
            if (const LightRow* m = cellOf(g, row, c))
                if (const std::optional<double> v = m->value(*spec.metric)) values.push_back(*v);
    return values;
}

std::string legend(const ColourScale& s, const MetricInfo& metric) {
    std::ostringstream o;
    o << "<div class=\"legend\"><span>" << num(s.lo)
      << "</span><span class=\"ramp\" style=\"background:" << rampGradient() << "\"></span><span>"
      << num(s.hi) << "</span><span class=\"note\">"
      << (s.log ? "log scale (a 0 takes the lowest colour)" : "linear scale") << "; "
      << betterName(metric.better) << " is better</span></div>";
    return o.str();
}

void writeHeader(std::ostream& o, const std::vector<IndexEntry>& entries, const Grid& g) {
    o << "<thead><tr><th rowspan=\"2\" class=\"corner\">technique</th>";
    for (size_t e = 0; e < entries.size(); ++e) {
        size_t lights = 0;
        for (const Column& c : g.columns) lights += c.entry == e;
        if (lights == 0) continue;
        o << "<th colspan=\"" << lights << "\" class=\"scene\" title=\""
          << html(entries[e].metrics.sceneFile) << "\"><a href=\""
          << html(urlEncode(entries[e].reportHref, "/")) << "\">"
          << html(sceneStem(entries[e].metrics.sceneFile)) << "</a></th>";
    }
    o << "</tr><tr>";
    for (const Column& c : g.columns)
        o << "<th class=\"light" << (c.firstOfScene ? " s" : "") << "\"><a href=\""
          << html(lightHref(entries[c.entry].reportHref, c.light)) << "\">" << html(c.light)
          << "</a></th>";
    o << "</tr></thead>";
}

void writeCell(std::ostream& o, const LightRow* m, const MetricSpec& spec, const ColourScale& scale,
               const Column& c, const std::string& href) {
    const char* rule = c.firstOfScene ? " s" : "";
    const std::optional<double> value = m ? m->value(*spec.metric) : std::nullopt;
    if (!value) {
        o << "<td class=\"na" << rule << "\"></td>";
        return;
    }
    const double v = *value;
    const std::optional<double> frameMs = m->value("cost.frame_ms");
    const std::array<int, 3> bg = rampColour(scalePosition(scale, v));
    const std::string cost = frameMs ? " · " + num(*frameMs) + " ms" : "";
    o << "<td class=\"v" << rule << "\" style=\"background:" << hexColour(bg)
      << ";color:" << textColour(bg) << "\" title=\"" << spec.metric->name << " " << v
      << (frameMs ? ", frame " + num(*frameMs) + " ms" : "") << "\"><a href=\"" << html(href)
      << "\">" << num(v) << cost << "</a></td>";
}

// One metric's matrix, or nothing when no cell has a value.
void writeMatrix(std::ostream& o, const std::vector<IndexEntry>& entries, const Grid& g,
                 const MetricSpec& spec) {
    const std::vector<double> values = valuesOf(g, spec);
    if (values.empty()) return;
    const ColourScale scale = scaleOf(values);
    o << "<section id=\"" << spec.metric->name << "\"><h2>" << spec.title << " <code>"
      << spec.metric->name << "</code></h2><p>" << html(spec.metric->description) << ".</p>"
      << legend(scale, *spec.metric);
    o << "<div class=\"scroll\"><table class=\"matrix\" data-metric=\"" << spec.metric->name
      << "\">";
    writeHeader(o, entries, g);
    o << "<tbody>";
    for (const std::string& row : g.rows) {
        o << "<tr><th scope=\"row\">" << html(row) << "</th>";
        for (const Column& c : g.columns)
            writeCell(o, cellOf(g, row, c), spec, scale, c,
                      lightHref(entries[c.entry].reportHref, c.light));
        o << "</tr>";
    }
    o << "</tbody></table></div></section>\n";
}

constexpr const char* kStyle = R"(<style>
body{font-family:system-ui,sans-serif;margin:1.5em;color:#222;max-width:100%}
h1{font-size:1.4em}h2{font-size:1.15em;margin-top:1.8em}
.scroll{overflow-x:auto}
table.matrix{border-collapse:collapse;font-size:12px}
.matrix th,.matrix td{border:1px solid #fff;padding:3px 6px;white-space:nowrap}
.matrix td{text-align:right;font-variant-numeric:tabular-nums}
.matrix td a{color:inherit;text-decoration:none;display:block}
.matrix td a:hover{text-decoration:underline}
.matrix tbody th{text-align:left;font-weight:normal;background:#f3f3f3;position:sticky;left:0}
.matrix thead th{background:#e8e8e8}
.matrix td.na{background:repeating-linear-gradient(45deg,#eee,#eee 4px,#f8f8f8 4px,#f8f8f8 8px)}
.legend{display:flex;align-items:center;gap:.5em;font-size:12px;margin:.4em 0}
.legend .ramp{display:inline-block;width:220px;height:12px;border:1px solid #999}
.legend .note{color:#555}
.matrix .s{border-left:2px solid #777}
.matrix thead th.scene{border-left:2px solid #777}
nav a{margin-right:1em}
</style>)";

void writeIntro(std::ostream& o, const std::vector<IndexEntry>& entries) {
    o << "<h1>Shadow techniques against the ray-traced oracle: " << entries.size()
      << (entries.size() == 1 ? " scene" : " scenes") << "</h1>";
    o << "<p><b>How to read:</b> each table is one artifact metric; a row is a technique setting, "
         "a column one light of one scene. A cell shows the metric's value, then the setting's "
         "median frame time for that light. <b>Lower is better for every metric here.</b> The "
         "colour places the value within the range of its own table, from dark purple (the lowest "
         "error there) through blue and green to yellow (the highest); a table whose values span "
         "more than a decade is coloured on a log scale, zeros taking the lowest colour. A blank "
         "hatched cell: the metric does not apply there (null in metrics.json, e.g. "
         "<code>penumbra_mae</code> of a hard light) or the setting was not run on that scene. A "
         "cell opens that light in the scene's report, a scene's name its whole report.</p>";
    std::vector<std::string> renderers;
    for (const IndexEntry& e : entries)
        if (!e.metrics.timedOn.empty() &&
            std::find(renderers.begin(), renderers.end(), e.metrics.timedOn) == renderers.end())
            renderers.push_back(e.metrics.timedOn);
    if (!renderers.empty()) {
        o << "<p>Times were measured on ";
        for (size_t i = 0; i < renderers.size(); ++i)
            o << (i ? ", " : "") << "<b>" << html(renderers[i]) << "</b>";
        o << (renderers.size() > 1 ? " (compare times only between runs on the same renderer)" : "")
          << ".</p>";
    }
}

}  // namespace

SceneMetrics parseSceneMetrics(const json& metrics, const std::string& path) {
    const JsonReader r(path);
    r.requireObject(metrics, "");
    const json* version = JsonReader::find(metrics, "schema_version");
    // 1 to 5 keep the names read here (docs/metrics.md, Versions); a later one may not.
    if (!version || !version->is_number_integer() || *version < 1 ||
        *version > kMetricsSchemaVersion)
        r.fail("schema_version", "not a metrics.json of schema_version 1 to " +
                                     std::to_string(kMetricsSchemaVersion));
    SceneMetrics out;
    out.path = path;
    out.schemaVersion = version->get<int>();
    const json& scene = r.at(metrics, "", "scene");
    r.requireObject(scene, "scene");
    out.sceneFile = optionalString(scene, "file", r, "scene");
    if (out.sceneFile.empty()) r.fail("scene.file", "missing");
    if (const json* gl = JsonReader::find(metrics, "gl"); gl && gl->is_object())
        out.timedOn = optionalString(*gl, "renderer", r, "gl");
    const json& results = r.at(metrics, "", "results");
    r.requireArray(results, "results");
    for (size_t i = 0; i < results.size(); ++i) {
        out.results.push_back(readResultRow(results[i], r, JsonReader::index("results", i)));
        for (const LightRow& m : out.results.back().lights)
            if (std::find(out.lights.begin(), out.lights.end(), m.light) == out.lights.end())
                out.lights.push_back(m.light);
    }
    return out;
}

SceneMetrics readSceneMetrics(const std::string& path) {
    std::ifstream in(path);
    if (!in) throwInputError(path, "", "cannot be read");
    json j;
    try {
        j = json::parse(in);
    } catch (const json::exception& e) {
        throwInputError(path, "", "invalid JSON: " + printable(e.what(), 160));
    }
    return parseSceneMetrics(j, path);
}

std::string sceneStem(const std::string& sceneFile) {
    std::string stem = std::filesystem::path(sceneFile).filename().string();
    for (const char* ext : {".json", ".gltf", ".glb"})
        if (stem.size() > std::string(ext).size() &&
            stem.compare(stem.size() - std::string(ext).size(), std::string::npos, ext) == 0) {
            stem.resize(stem.size() - std::string(ext).size());
            break;
        }
    // Scene files are named NAME.scene.json (scenes/): the ".scene" says nothing in a header.
    const std::string scene = ".scene";
    if (stem.size() > scene.size() &&
        stem.compare(stem.size() - scene.size(), std::string::npos, scene) == 0)
        stem.resize(stem.size() - scene.size());
    return stem;
}

const std::vector<std::string>& indexMetricNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const MetricSpec& s : metricSpecs()) n.push_back(s.metric->name);
        return n;
    }();
    return names;
}

std::string indexPageHtml(const std::vector<IndexEntry>& entries) {
    std::ostringstream o;
    o << "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadow-oracle "
         "index: "
      << entries.size() << (entries.size() == 1 ? " scene" : " scenes") << "</title>" << kStyle
      << "</head><body>\n";
    writeIntro(o, entries);
    const Grid grid = gridOf(entries);
    std::ostringstream matrices;
    o << "<nav>";
    for (const MetricSpec& spec : metricSpecs()) {
        const std::streampos before = matrices.tellp();
        writeMatrix(matrices, entries, grid, spec);
        if (matrices.tellp() != before)
            o << "<a href=\"#" << spec.metric->name << "\">" << spec.title << "</a>";
    }
    o << "</nav>\n" << matrices.str() << "</body></html>\n";
    return o.str();
}

void writeIndexPage(const std::string& path, const std::vector<IndexEntry>& entries) {
    const std::string page = indexPageHtml(entries);
    std::ofstream f(path);
    if (!f) throwInputError(path, "index page", "cannot be written");
    f << page;
    if (!f) throwInputError(path, "index page", "cannot be written");
}

}  // namespace so
