// The sweep's report (raster_compare/compare/sweep_report.h): a hand-made sweep whose Pareto
// fronts, cheapest settings, heat maps and "no acne, least peter-panning" answers are worked out
// below, read back from the written page.
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "raster_compare/compare/sweep_report.h"

namespace so::test {
namespace {

constexpr double kMiB = 1048576.0;

ParamValue number(double v) {
    return {ParamValue::Kind::Number, v, ""};
}

void setMetric(SweepRow& r, const std::string& name, double v) {
    r.result.lights.front().set(metricInfo(name), v);
}

SweepRow row(const std::string& light, const std::string& technique, const std::string& label,
             std::vector<std::pair<std::string, ParamValue>> swept, double acne, double pp,
             double mae, double ms, double mib) {
    SweepRow r;
    r.task = "t-" + label;
    r.scene = "scenes/box.scene.json";
    r.result.technique = technique;
    r.result.label = label;
    r.result.lights.emplace_back();
    r.result.lights.front().light = light;
    r.swept = std::move(swept);
    setMetric(r, "acne_rate", acne);
    setMetric(r, "peter_panning_rate", pp);
    setMetric(r, "mae", mae);
    setMetric(r, "cost.frame_ms", ms);
    setMetric(r, "cost.memory_bytes", mib * kMiB);
    return r;
}

SweepRow slopeBias(const std::string& light, double alpha, double min, double acne, double pp,
                   double mae, double ms, double mib = 4.0) {
    std::ostringstream label;
    label << "slope-bias:alpha=" << alpha << ",min=" << min;
    return row(light, "slope-bias", label.str(), {{"alpha", number(alpha)}, {"min", number(min)}},
               acne, pp, mae, ms, mib);
}

// Light "key": slope-bias alpha {0, 1, 2} x min {0, 0.5}, pcf over kernel {3, 5}, and basic.
// By frame time the mae front is basic (0.5 ms, 0.2), then slope-bias (0,0) 0.1, (0,0.5) 0.06,
// (1,0) 0.03, (1,0.5) 0.02 (its 1.3 ms tie with (2,0) goes to the lower error), then pcf 5
// (3 ms, 0.015). Among the acne-free settings ((1,0.5), (2,0), (2,0.5)) the least peter-panning
// is (2,0): 0.003, though (0,0) has less (0) with acne. Light "fill": every slope-bias setting
// has acne.
SweepReportInput sweep() {
    SweepReportInput in;
    in.specFile = "sweeps/bias.sweep.json";
    in.sweepName = "bias <b>study</b>";
    in.errorBudgets = {0.0, 0.03, 0.1};
    in.timedOn = "Test GPU";
    const std::string k = "key";
    in.rows = {row(k, "basic", "basic", {}, 0.3, 0.0, 0.2, 0.5, 4.0),
               slopeBias(k, 0, 0, 0.2, 0.0, 0.1, 1.0),
               slopeBias(k, 0, 0.5, 0.05, 0.001, 0.06, 1.1),
               slopeBias(k, 1, 0, 0.01, 0.002, 0.03, 1.2),
               slopeBias(k, 1, 0.5, 0.0, 0.004, 0.02, 1.3),
               slopeBias(k, 2, 0, 0.0, 0.003, 0.025, 1.3, 2.0),
               slopeBias(k, 2, 0.5, 0.0, 0.008, 0.04, 1.5),
               row(k, "pcf", "pcf:kernel=3", {{"kernel", number(3)}}, 0.001, 0.01, 0.05, 2.0, 8.0),
               row(k, "pcf", "pcf:kernel=5", {{"kernel", number(5)}}, 0.0, 0.02, 0.015, 3.0, 8.0)};
    for (double alpha : {0.0, 1.0})
        for (double min : {0.0, 0.5})
            in.rows.push_back(slopeBias("fill", alpha, min, 0.01 + alpha, 0.0, 0.1, 1.0));
    std::set<std::string> tasks;
    for (const SweepRow& r : in.rows) tasks.insert(r.task);
    in.tasks = tasks.size() + 1;
    in.failed = {{"t-0042", "scenes/box.scene.json", "pcf:kernel=<script>alert(1)</script>",
                  "exit 2: GL context lost", "logs/t-0042 pcf.log"}};
    in.provenance = {{"commit", "abc123"}, {"note", "<script>alert(2)</script>"}};
    return in;
}

std::string writeAndRead(const SweepReportInput& in) {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("sweep_report_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".html");
    writeSweepReport(path.string(), in);
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    std::filesystem::remove(path);
    return s.str();
}

// The text from the first `start` on to the first `end` after it (inclusive), or "".
std::string between(const std::string& page, const std::string& start, const std::string& end) {
    const size_t a = page.find(start);
    if (a == std::string::npos) return "";
    const size_t b = page.find(end, a);
    return b == std::string::npos ? "" : page.substr(a, b + end.size() - a);
}

std::vector<std::string> matches(const std::string& text, const std::string& pattern) {
    std::vector<std::string> out;
    const std::regex re(pattern);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
         ++it)
        out.push_back((*it)[1]);
    return out;
}

std::string section(const std::string& page, int index) {
    return between(page, "<section id=\"light-" + std::to_string(index) + "\"", "</section>");
}

TEST(SweepReport, FrontTableListsExactlyTheUnbeatenSettings) {
    const std::string key = section(writeAndRead(sweep()), 0);
    ASSERT_NE(key.find("light key"), std::string::npos);
    const std::string byTime = between(
        key, "<table class=\"front\" data-metric=\"mae\" data-cost=\"cost.frame_ms\">", "</table>");
    EXPECT_EQ(matches(byTime, "<td class=\"text label\">([^<]*)</td>"),
              (std::vector<std::string>{"basic", "slope-bias:alpha=0,min=0",
                                        "slope-bias:alpha=0,min=0.5", "slope-bias:alpha=1,min=0",
                                        "slope-bias:alpha=1,min=0.5", "pcf:kernel=5"}));
    // By memory (MiB): (2,0) alone at 2 MiB, then the best at 4 MiB, then pcf 5 at 8.
    const std::string byMemory =
        between(key, "<table class=\"front\" data-metric=\"mae\" data-cost=\"cost.memory_bytes\">",
                "</table>");
    EXPECT_EQ(matches(byMemory, "<td class=\"text label\">([^<]*)</td>"),
              (std::vector<std::string>{"slope-bias:alpha=2,min=0", "slope-bias:alpha=1,min=0.5",
                                        "pcf:kernel=5"}));
    EXPECT_EQ(matches(byMemory, "<td data-v=\"([^\"]*)\">")[0], "2") << "memory shown in MiB";
    EXPECT_NE(key.find("<svg class=\"front-chart\""), std::string::npos);
}

// A work axis (docs/metrics.md, Work): the front and the budget table by bytes moved, where pcf 3
// moves the least and slope-bias the most: the order of frame time turned round.
TEST(SweepReport, FrontsAndBudgetsAgainstTheWorkOfAFrame) {
    SweepReportInput in = sweep();
    for (SweepRow& r : in.rows)
        setMetric(r, "cost.work.bytes_moved",
                  (r.result.technique == "pcf"     ? 1.0
                   : r.result.technique == "basic" ? 3.0
                                                   : 2.0) *
                      kMiB);
    const std::string key = section(writeAndRead(in), 0);
    const std::string front = between(
        key, "<table class=\"front\" data-metric=\"mae\" data-cost=\"cost.work.bytes_moved\">",
        "</table>");
    // pcf 3 and 5 move 1 MiB alike: the front is pcf 5 (0.015) alone, shown in MiB.
    EXPECT_EQ(matches(front, "<td class=\"text label\">([^<]*)</td>"),
              (std::vector<std::string>{"pcf:kernel=5"}));
    EXPECT_EQ(matches(front, "<td data-v=\"([^\"]*)\">")[0], "1");
    EXPECT_NE(key.find("<option value=\"cost.work.bytes_moved\">bytes moved</option>"),
              std::string::npos);
    // Its budget table: slope-bias's cheapest within 0.1 by bytes (2 MiB each, ties by memory:
    // (2,0) holds 2 MiB); a fragments table is absent, since no row has fragments.
    const std::string budgets =
        between(key, "<div class=\"budget-box\" data-cost=\"cost.work.bytes_moved\">", "</div>");
    const std::string mae =
        between(budgets, "data-technique=\"slope-bias\" data-metric=\"mae\">", "</tr>");
    EXPECT_EQ(matches(mae, "<td class=\"text[^\"]*\"[^>]*>([^<]*)").back(), "alpha=2,min=0 ");
    EXPECT_EQ(key.find("data-cost=\"cost.work.fragments\""), std::string::npos);
}

TEST(SweepReport, CheapestSettingAtEachBudget) {
    const std::string key = section(writeAndRead(sweep()), 0);
    const std::string mae =
        between(key, "data-technique=\"slope-bias\" data-metric=\"mae\">", "</tr>");
    // Budgets 0, 0.03, 0.1: none reaches 0; (1,0) at 1.2 ms; (0,0) at 1 ms.
    EXPECT_EQ(matches(mae, "<td class=\"text[^\"]*\"[^>]*>([^<]*)"),
              (std::vector<std::string>{"mae", "none", "alpha=1,min=0 ", "alpha=0,min=0 "}));
    // Acne 0 at 1.3 ms twice: (2,0) holds less memory than (1,0.5).
    const std::string acne =
        between(key, "data-technique=\"slope-bias\" data-metric=\"acne_rate\">", "</tr>");
    EXPECT_EQ(matches(acne, "<td class=\"text[^\"]*\"[^>]*>([^<]*)").at(1), "alpha=2,min=0 ");
}

TEST(SweepReport, HeatMapHasOneCellPerSettingWithItsValue) {
    const std::string key = section(writeAndRead(sweep()), 0);
    const std::string acne = between(
        key, "<table class=\"heat\" data-technique=\"slope-bias\" data-metric=\"acne_rate\">",
        "</table>");
    // Rows alpha 0, 1, 2; columns min 0, 0.5.
    EXPECT_EQ(matches(acne, "<th>([^<]*)</th>"),
              (std::vector<std::string>{"0", "0.5", "0", "1", "2"}));
    EXPECT_EQ(matches(acne, "data-v=\"([^\"]*)\""),
              (std::vector<std::string>{"0.2", "0.05", "0.01", "0", "0", "0"}));
    EXPECT_EQ(matches(acne, "<td class=\"cell([^\"]*)\"").size(), 6u);
    EXPECT_EQ(matches(acne, "class=\"cell best( clean)\"").size(), 3u)
        << "every acne-free cell is both the lowest and marked clean";
    const std::string pp = between(
        key,
        "<table class=\"heat\" data-technique=\"slope-bias\" data-metric=\"peter_panning_rate\">",
        "</table>");
    EXPECT_EQ(matches(pp, "<td class=\"cell( best)\" data-v=\"([^\"]*)\"").size(), 1u);
    EXPECT_NE(pp.find("<td class=\"cell best\" data-v=\"0\""), std::string::npos);
    EXPECT_EQ(pp.find("clean"), std::string::npos) << "only the acne map marks acne-free cells";
    EXPECT_NE(key.find("<table class=\"heat one\" data-technique=\"pcf\">"), std::string::npos)
        << "one swept parameter: a table against it";
}

TEST(SweepReport, NamesTheAcneFreeSettingWithTheLeastPeterPanning) {
    const std::string page = writeAndRead(sweep());
    EXPECT_NE(section(page, 0).find("<li class=\"verdict\" data-technique=\"slope-bias\">"
                                    "slope-bias: alpha=2, min=0 has no acne and the least "
                                    "peter-panning (0.003)</li>"),
              std::string::npos);
    EXPECT_NE(
        section(page, 0).find("pcf: kernel=5 has no acne and the least peter-panning (0.02)</li>"),
        std::string::npos);
    EXPECT_NE(section(page, 1).find("slope-bias: every setting has acne</li>"), std::string::npos);
    EXPECT_EQ(page.find("class=\"verdict\" data-technique=\"basic\""), std::string::npos)
        << "nothing swept: no sentence";
}

// A parameter that picks a method is typed by its name where the row is made (metrics.json holds
// its index): the sentence and the table write that name, as the label does.
TEST(SweepReport, NamedParametersAreWrittenByName) {
    SweepReportInput in = sweep();
    in.rows.push_back(row("key", "raytraced", "raytraced:denoiser=none,spp=1",
                          {{"denoiser", {ParamValue::Kind::Name, 0, "none"}}}, 0.0, 0.01, 0.05, 1.0,
                          1.0));
    in.rows.push_back(row("key", "raytraced", "raytraced:denoiser=svgf,spp=1",
                          {{"denoiser", {ParamValue::Kind::Name, 2, "svgf"}}}, 0.0, 0.002, 0.03,
                          2.0, 1.0));
    const std::string key = section(writeAndRead(in), 0);
    EXPECT_NE(key.find("raytraced: denoiser=svgf has no acne and the least peter-panning"),
              std::string::npos);
    const std::string table =
        between(key, "<table class=\"heat one\" data-technique=\"raytraced\">", "</table>");
    EXPECT_EQ(matches(table, "<tr><th>([^<]*)</th>"), (std::vector<std::string>{"none", "svgf"}));
}

TEST(SweepReport, EscapesUserTextAndListsFailedTasksWithTheirLogs) {
    const std::string page = writeAndRead(sweep());
    EXPECT_EQ(page.find("<script>alert"), std::string::npos);
    EXPECT_EQ(page.find("<b>study"), std::string::npos);
    EXPECT_NE(page.find("pcf:kernel=&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
    EXPECT_NE(page.find("&lt;script&gt;alert(2)&lt;/script&gt;"), std::string::npos);
    const std::string failed = between(page, "<div class=\"failed-box\"", "</div>");
    EXPECT_NE(failed.find("1 task failed"), std::string::npos);
    EXPECT_NE(failed.find("t-0042"), std::string::npos);
    EXPECT_NE(failed.find("exit 2: GL context lost"), std::string::npos);
    EXPECT_NE(failed.find("<a href=\"logs/t-0042%20pcf.log\">"), std::string::npos);
    EXPECT_NE(page.find("9 of 10 tasks finished"), std::string::npos);
}

TEST(SweepReport, NoFailedBoxWhenEveryTaskFinished) {
    SweepReportInput in = sweep();
    in.failed.clear();
    in.tasks = 9;
    const std::string page = writeAndRead(in);
    EXPECT_EQ(page.find("<div class=\"failed-box\""), std::string::npos);
    EXPECT_NE(page.find("9 of 9 tasks finished"), std::string::npos);
}

}  // namespace
}  // namespace so::test

namespace so::test {
namespace {

// A row that grades a variant or a design of our own is marked after its label on the fronts
// (issue 63); a faithful row, or one without provenance, is not.
TEST(SweepReport, MarksRowsThatAreNotTheirAnchorsDesign) {
    SweepReportInput in = sweep();
    for (SweepRow& r : in.rows)
        if (r.result.label == "pcf:kernel=5") {
            r.result.fidelity = "variant";
            r.result.provenanceText = "technique pcf: variant, <Reeves>";
        } else if (r.result.technique == "basic") {
            r.result.fidelity = "faithful";
        }
    const std::string key = section(writeAndRead(in), 0);
    const std::string byTime = between(
        key, "<table class=\"front\" data-metric=\"mae\" data-cost=\"cost.frame_ms\">", "</table>");
    EXPECT_NE(byTime.find("pcf:kernel=5 <sup class=\"fidelity\" data-fidelity=\"variant\" "
                          "title=\"technique pcf: variant, &lt;Reeves&gt;\">variant</sup>"),
              std::string::npos)
        << byTime;
    EXPECT_EQ(matches(byTime, "data-fidelity=\"([a-z]*)\"").size(), 1u) << byTime;
}

}  // namespace
}  // namespace so::test
