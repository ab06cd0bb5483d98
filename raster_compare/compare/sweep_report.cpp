// The HTML report of a sweep (sweep_report.h; docs/sweep.md, "The report"). Every chart is drawn
// as a table or inline SVG (sweep_fronts.cpp, sweep_grids.cpp), so the page reads the same without
// script; the one small script only narrows the front charts to one artifact.
#include "raster_compare/compare/sweep_report.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "raster_compare/compare/contact_pairs.h"
#include "raster_compare/compare/html.h"
#include "raster_compare/compare/result_row.h"
#include "raster_compare/compare/sweep_sections.h"

namespace so {

namespace {

using namespace sweep;

// In the order the rows first name them: the merge keeps the spec's order.
std::vector<Group> groupsOf(const SweepReportInput& in) {
    std::vector<Group> groups;
    for (const SweepRow& r : in.rows) {
        auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
            return g.scene == r.scene && g.light == r.light().light;
        });
        if (it == groups.end())
            it = groups.insert(groups.end(), Group{r.scene, r.light().light, {}});
        it->rows.push_back(&r);
    }
    return groups;
}

// Okabe-Ito (colour-blind safe, as the artifact colours in artifacts.h), yellow last as it is
// faint on white; black is left to the front's line. Techniques take them in first-seen order,
// the same in every section.
ColourMap techniqueColours(const SweepReportInput& in) {
    static const std::array<const char*, 8> palette = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                                       "#e69f00", "#56b4e9", "#999999", "#f0e442"};
    ColourMap colours;
    for (const SweepRow& r : in.rows)
        colours.emplace(r.result.technique, palette[colours.size() % palette.size()]);
    return colours;
}

// ---- the page ----

constexpr const char* kStyle = R"(<style>
body{font-family:system-ui,sans-serif;margin:1.5em;color:#222}
h1{font-size:1.4em}h2{font-size:1.2em;margin-top:2em;border-top:1px solid #ccc;padding-top:.6em}
h3{font-size:1.05em;margin-top:1.4em}h4{font-size:.95em;margin:1em 0 .3em}
.muted{color:#666;font-size:.9em}
sup.fidelity{color:#9a4d00;font-size:.75em;cursor:help}
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
    o << "<li><a href=\"#provenance\">run provenance</a></li></ol></nav>";
}

void writeGroup(std::ostream& o, const Group& g, size_t gi, const SweepReportInput& in,
                const ColourMap& colours) {
    o << "<section id=\"" << groupId(gi) << "\"><h2>" << html(g.scene) << " &mdash; light "
      << html(g.light) << "</h2><p class=\"muted\">" << g.rows.size() << " settings of "
      << techniquesOf(g.rows).size() << " techniques.</p>";
    writeVerdicts(o, g);
    std::vector<ContactSetting> settings;
    for (const SweepRow* r : g.rows) settings.push_back({&r->result, &r->light()});
    writeContactTable(o, pairContactSettings(settings));
    writeFronts(o, g, in, colours);
    writeBudgets(o, g, in.errorBudgets);
    writeHeatMaps(o, g);
    o << "</section>\n";
}

void writeTail(std::ostream& o, const SweepReportInput& in) {
    o << "<h2 id=\"provenance\">Run provenance</h2><table class=\"provenance\">";
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
