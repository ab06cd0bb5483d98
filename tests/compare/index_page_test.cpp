// The index page over many compare runs (raster_compare/compare/index_page.h): two hand-made
// metrics.json objects whose matrices, links, empty cells and colours are known, and malformed
// files whose errors must name the file and the field.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "raster_compare/compare/index_page.h"
#include "raster_compare/compare/metrics.h"

namespace so::test {
namespace {

using nlohmann::json;

json lightMetrics(json mae, json acne, json penumbra, json frameMs) {
    return {{"mae", mae},
            {"acne_rate", acne},
            {"peter_panning_rate", 0.0},
            {"boundary_displacement_px", {{"mean", 1.0}, {"p95", 2.5}, {"max", 4.0}}},
            {"light_bleeding_rate", nullptr},
            {"penumbra_mae", penumbra},
            {"cost", {{"frame_ms", frameMs}, {"shadow_map_ms", 1.0}}}};
}

// Scene alpha: one hard light, two settings. Light bleeding is null everywhere (no filtered
// technique), so its matrix must be left out.
json alphaMetrics() {
    json m = {{"schema_version", 4},
              {"scene", {{"file", "scenes/alpha.scene.json"}}},
              {"gl", {{"renderer", "test renderer"}}}};
    m["results"] = json::array();
    m["results"].push_back({{"label", "basic"},
                            {"technique", "basic"},
                            {"family", "shadow map"},
                            {"lights", {{"key", lightMetrics(0.2, 0.3, nullptr, 3.4)}}}});
    m["results"].push_back({{"label", "slope-bias"},
                            {"technique", "slope-bias"},
                            {"lights", {{"key", lightMetrics(0.01, 0.002, nullptr, 2.0)}}}});
    return m;
}

// Scene beta: an area light ("area lamp", a space in its name) and a hard one; pcss only here,
// slope-bias not run here.
json betaMetrics() {
    json m = {{"schema_version", 3}, {"scene", {{"file", "scenes/beta.scene.json"}}}};
    m["results"] = json::array();
    m["results"].push_back({{"label", "basic"},
                            {"technique", "basic"},
                            {"lights",
                             {{"area lamp", lightMetrics(0.1, nullptr, 0.15, 5.0)},
                              {"sun", lightMetrics(0.05, 0.1, nullptr, 5.0)}}}});
    m["results"].push_back({{"label", "pcss:filter_samples=8"},
                            {"technique", "pcss"},
                            {"lights",
                             {{"area lamp", lightMetrics(0.02, nullptr, 0.03, nullptr)},
                              {"sun", lightMetrics(0.04, nullptr, nullptr, 7.25)}}}});
    return m;
}

std::string page() {
    return indexPageHtml(
        {{parseSceneMetrics(alphaMetrics(), "alpha/metrics.json"), "alpha/report.html"},
         {parseSceneMetrics(betaMetrics(), "runs/beta/metrics.json"), "runs/beta/report.html"}});
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

std::string matrix(const std::string& html, const std::string& metric) {
    const size_t begin = html.find("<table class=\"matrix\" data-metric=\"" + metric + "\">");
    if (begin == std::string::npos) return "";
    return html.substr(begin, html.find("</table>", begin) - begin);
}

// The <td ...>...</td> cells of the row headed `label`.
std::vector<std::string> rowCells(const std::string& table, const std::string& label) {
    const size_t row = table.find("<th scope=\"row\">" + label + "</th>");
    if (row == std::string::npos) return {};
    const std::string tr = table.substr(row, table.find("</tr>", row) - row);
    std::vector<std::string> cells;
    for (size_t p = tr.find("<td"); p != std::string::npos; p = tr.find("<td", p + 1))
        cells.push_back(tr.substr(p, tr.find("</td>", p) - p));
    return cells;
}

TEST(IndexPage, OneMatrixPerMetricWithAValue) {
    const std::string html = page();
    // Every cell null (these runs had no filtered technique, no --sequence): left out.
    EXPECT_EQ(count(html, "<table class=\"matrix\""), indexMetricNames().size() - 3);
    for (const char* metric : {"light_bleeding_rate", "sequence.mae_mean", "sequence.lag_mae"})
        EXPECT_EQ(matrix(html, metric), "") << metric;
    for (const char* metric :
         {"mae", "acne_rate", "peter_panning_rate", "boundary_displacement_px.p95", "penumbra_mae"})
        EXPECT_NE(matrix(html, metric), "") << metric;
    EXPECT_NE(html.find("Lower is better"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos) << "self-contained: no network";
}

TEST(IndexPage, RowsAreTheUnionOfLabelsAndColumnsEverySceneLight) {
    const std::string mae = matrix(page(), "mae");
    EXPECT_EQ(count(mae, "<th scope=\"row\">"), 3u);
    EXPECT_LT(mae.find(">basic<"), mae.find(">slope-bias<")) << "first-seen order";
    EXPECT_LT(mae.find(">slope-bias<"), mae.find(">pcss:filter_samples=8<"));
    EXPECT_EQ(count(mae, "<th class=\"light"), 3u);
    EXPECT_EQ(count(mae, "<td"), 9u);
    EXPECT_NE(mae.find(">alpha</a>"), std::string::npos) << "the stem, without .scene.json";
}

TEST(IndexPage, LinksToTheReportsAndTheirLights) {
    const std::string mae = matrix(page(), "mae");
    EXPECT_NE(mae.find("<a href=\"alpha/report.html\">"), std::string::npos);
    EXPECT_NE(mae.find("<a href=\"runs/beta/report.html\">"), std::string::npos);
    const std::vector<std::string> basic = rowCells(mae, "basic");
    ASSERT_EQ(basic.size(), 3u);
    EXPECT_NE(basic[0].find("href=\"alpha/report.html#light-key\""), std::string::npos);
    EXPECT_NE(basic[1].find("href=\"runs/beta/report.html#light-area%20lamp\""), std::string::npos);
    EXPECT_NE(basic[0].find(">0.2 · 3.4 ms</a>"), std::string::npos) << basic[0];
}

TEST(IndexPage, NullsAndMissingRunsAreEmptyCells) {
    const std::string html = page();
    const std::vector<std::string> slope = rowCells(matrix(html, "acne_rate"), "slope-bias");
    ASSERT_EQ(slope.size(), 3u);
    EXPECT_EQ(slope[0].find("class=\"na\""), std::string::npos);
    EXPECT_EQ(slope[1], "<td class=\"na s\">") << "not run on beta (its first column: a rule)";
    const std::vector<std::string> basic = rowCells(matrix(html, "acne_rate"), "basic");
    ASSERT_EQ(basic.size(), 3u);
    EXPECT_EQ(basic[1], "<td class=\"na s\">") << "acne_rate null on the area light";
    EXPECT_EQ(basic[2].find("class=\"na"), std::string::npos);
    const std::vector<std::string> pcssAcne =
        rowCells(matrix(html, "acne_rate"), "pcss:filter_samples=8");
    ASSERT_EQ(pcssAcne.size(), 3u);
    EXPECT_EQ(pcssAcne[2], "<td class=\"na\">") << "acne_rate null on sun";
    const std::vector<std::string> pcss = rowCells(matrix(html, "mae"), "pcss:filter_samples=8");
    ASSERT_EQ(pcss.size(), 3u);
    EXPECT_NE(pcss[1].find(">0.02</a>"), std::string::npos) << "no frame_ms: the value alone";
}

// The lowest value of a matrix takes the ramp's first colour, the highest its last; acne spans
// 0.002 .. 0.3, more than a decade, so its scale is logarithmic.
TEST(IndexPage, ColoursSpanTheMatrixRange) {
    const std::string html = page();
    const std::string acne = matrix(html, "acne_rate");
    EXPECT_NE(rowCells(acne, "slope-bias")[0].find("background:#440154"), std::string::npos);
    EXPECT_NE(rowCells(acne, "basic")[0].find("background:#fde725"), std::string::npos);
    const size_t section = html.find("<section id=\"acne_rate\">");
    ASSERT_NE(section, std::string::npos);
    EXPECT_NE(html.substr(section, html.find("<table", section) - section).find("log scale"),
              std::string::npos);
    const std::string pp = matrix(html, "peter_panning_rate");
    EXPECT_NE(rowCells(pp, "basic")[0].find("background:#440154"), std::string::npos)
        << "all equal: the lowest colour";
}

void expectInputError(const json& metrics, const std::string& field) {
    try {
        parseSceneMetrics(metrics, "some/run/metrics.json");
        ADD_FAILURE() << "no error for a bad " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "some/run/metrics.json");
        EXPECT_EQ(e.field(), field) << e.what();
        EXPECT_NE(std::string(e.what()).find("some/run/metrics.json: " + field), std::string::npos)
            << e.what();
    }
}

TEST(IndexPage, MalformedMetricsNameTheFileAndField) {
    json noResults = alphaMetrics();
    noResults.erase("results");
    expectInputError(noResults, "results");
    json newer = alphaMetrics();
    newer["schema_version"] = kMetricsSchemaVersion + 1;
    expectInputError(newer, "schema_version");
    json noVersion = alphaMetrics();
    noVersion.erase("schema_version");
    expectInputError(noVersion, "schema_version");
    json stringMae = alphaMetrics();
    stringMae["results"][1]["lights"]["key"]["mae"] = "small";
    expectInputError(stringMae, "results[1].lights.key.mae");
    json badP95 = alphaMetrics();
    badP95["results"][0]["lights"]["key"]["boundary_displacement_px"]["p95"] = true;
    expectInputError(badP95, "results[0].lights.key.boundary_displacement_px.p95");
    json noScene = alphaMetrics();
    noScene["scene"].erase("file");
    expectInputError(noScene, "scene.file");
}

TEST(IndexPage, ReadsAllFieldsAndNulls) {
    const SceneMetrics m = parseSceneMetrics(betaMetrics(), "beta/metrics.json");
    EXPECT_EQ(m.schemaVersion, 3);
    EXPECT_EQ(m.sceneFile, "scenes/beta.scene.json");
    EXPECT_EQ(m.lights, (std::vector<std::string>{"area lamp", "sun"}));
    ASSERT_EQ(m.results.size(), 2u);
    const LightRow& lamp = m.results[1].lights[0];
    EXPECT_EQ(lamp.light, "area lamp");
    EXPECT_EQ(*lamp.value("penumbra_mae"), 0.03);
    EXPECT_EQ(*lamp.value("boundary_displacement_px.p95"), 2.5);
    EXPECT_FALSE(lamp.value("acne_rate"));
    EXPECT_FALSE(lamp.value("cost.frame_ms"));
    EXPECT_EQ(*m.results[1].lights[1].value("cost.frame_ms"), 7.25);
    EXPECT_EQ(sceneStem("scenes/terrain_sun.scene.json"), "terrain_sun");
    EXPECT_EQ(sceneStem("models/bunny.glb"), "bunny");
}

}  // namespace
}  // namespace so::test
