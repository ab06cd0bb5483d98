// The typed rows (raster_compare/compare/result_row.h): a metrics.json row read back keeps its
// parameters' kinds, tells a null metric from an absent one, and names the field of a bad value;
// the metric table carries the baseline's tolerances and the reports' cost axes.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_reader.h"
#include "raster_compare/compare/baseline.h"
#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/result_row.h"

namespace so::test {
namespace {

using nlohmann::json;

json row() {
    return {{"technique", "pcf"},
            {"family", "shadow map"},
            {"label", "pcf:contact=on,bias=0.25"},
            {"parameters", {{"contact", 1}, {"bias", 0.25}, {"resolution", 2048}}},
            {"lights",
             {{"sun",
               {{"mae", 0.125},
                {"aliasing_rate", nullptr},
                {"penumbra_width_error_px", nullptr},
                {"boundary_displacement_px", {{"p95", 2.5}, {"missing_boundary", true}}},
                {"cost", {{"frame_ms", 3.5}, {"work", nullptr}, {"noisy", false}}}}}}}};
}

TEST(ResultRow, ReadsParametersWithTheirKindsAndMetricsByTheTable) {
    const ResultRow r = readResultRow(row(), JsonReader("m.json"), "results[0]");
    EXPECT_EQ(r.label, "pcf:contact=on,bias=0.25");
    EXPECT_EQ(r.family, "shadow map");
    EXPECT_EQ(r.parameters.at("resolution").kind, ParamValue::Kind::Integer);
    EXPECT_EQ(r.parameters.at("bias").kind, ParamValue::Kind::Number);
    EXPECT_EQ(r.parameters.at("bias").text(), "0.25");
    EXPECT_EQ(r.parameters.at("resolution").text(), "2048");
    ASSERT_EQ(r.lights.size(), 1u);
    const LightRow& sun = *r.light("sun");
    EXPECT_EQ(*sun.value("mae"), 0.125);
    EXPECT_EQ(*sun.value("cost.frame_ms"), 3.5);
    EXPECT_EQ(*sun.value("boundary_displacement_px.missing_boundary"), 1.0);
    EXPECT_EQ(*sun.value("cost.noisy"), 0.0);
    // Null is there but has no value; a member of a null group, and a key not written, are absent.
    EXPECT_TRUE(sun.has(metricInfo("aliasing_rate")));
    EXPECT_FALSE(sun.value("aliasing_rate"));
    EXPECT_FALSE(sun.has(metricInfo("penumbra_width_error_px.mean")));
    EXPECT_FALSE(sun.has(metricInfo("cost.work.fragments")));
    EXPECT_FALSE(sun.has(metricInfo("temporal_flicker_rate")));
}

TEST(ResultRow, MethodNamesAndTextParameters) {
    EXPECT_EQ((ParamValue{ParamValue::Kind::Name, 1, "on"}).text(), "on");
    EXPECT_EQ(paramValueOfJson("svgf").kind, ParamValue::Kind::Name);
    EXPECT_EQ(paramValueOfJson("svgf").text(), "svgf");
    EXPECT_EQ(paramValueOfJson(json(1.0 / 3.0)).text(), "0.3333333333333333");
    EXPECT_EQ(paramValueOfJson(json(1e20)).text(), "1e+20");
}

TEST(ResultRow, BadValuesNameTheirField) {
    const auto fieldOf = [](const json& j) {
        try {
            (void)readResultRow(j, JsonReader("m.json"), "results[3]");
        } catch (const InputError& e) {
            return e.field();
        }
        return std::string("no error");
    };
    json s = row();
    s["lights"]["sun"]["cost"]["frame_ms"] = "slow";
    EXPECT_EQ(fieldOf(s), "results[3].lights.sun.cost.frame_ms");
    json g = row();
    g["lights"]["sun"]["boundary_displacement_px"] = 2;
    EXPECT_EQ(fieldOf(g), "results[3].lights.sun.boundary_displacement_px");
    json f = row();
    f["lights"]["sun"]["mae"] = true;  // a boolean only for a flag
    EXPECT_EQ(fieldOf(f), "results[3].lights.sun.mae");
    json n = row();
    n.erase("label");
    n.erase("technique");
    EXPECT_EQ(fieldOf(n), "results[3].label");
}

// The metric table carries what the baseline and the reports used to list themselves.
TEST(ResultRow, TheTableCarriesTolerancesAndCostAxes) {
    const MetricInfo& frame = metricInfo("cost.frame_ms");
    EXPECT_EQ(frame.baseline.use, BaselineRule::WhenNamed);
    EXPECT_EQ(frame.baseline.tolerance.rel, 0.5);
    EXPECT_EQ(metricInfo("max_abs").baseline.noise, OracleNoise::WorstHalfWidth);
    EXPECT_EQ(metricInfo("counted_pixels").baseline.use, BaselineRule::Never);
    std::vector<std::string> sweep, report;
    for (const MetricInfo* m : costAxes(false)) sweep.push_back(m->name);
    for (const MetricInfo* m : costAxes(true)) report.push_back(m->name);
    EXPECT_EQ(sweep.front(), "cost.frame_ms");
    EXPECT_EQ(sweep[1], "cost.memory_bytes");
    EXPECT_EQ(sweep.back(), "cost.work.rays_traced");
    EXPECT_EQ(report.size(), sweep.size() + 2);  // and the shadow and visibility passes' times
    EXPECT_EQ(report[1], "cost.shadow_map_ms");
    // Every metric the baseline compares has a tolerance, the costs only when named.
    for (const MetricInfo* m : baselineMetricTable())
        EXPECT_EQ(m->baseline.use == BaselineRule::WhenNamed,
                  std::string(m->name).rfind("cost.", 0) == 0)
            << m->name;
}

}  // namespace
}  // namespace so::test

namespace so::test {
namespace {

// metrics.json's "provenance" (issue 63): the row's fidelity and its parts as the reports' tooltip;
// none for an older file; a malformed one names its field.
TEST(ResultRow, ReadsProvenance) {
    json j = row();
    EXPECT_EQ(readResultRow(j, JsonReader("m.json"), "results[0]").fidelity, "");
    j["provenance"] = {
        {"fidelity", "variant"},
        {"parts",
         {{{"of", "technique pcf"}, {"anchor", "Reeves 1987"}, {"fidelity", "faithful"}},
          {{"of", "bias=x"},
           {"anchor", "paper"},
           {"fidelity", "variant"},
           {"deviations", {"one"}}}}}};
    const ResultRow r = readResultRow(j, JsonReader("m.json"), "results[0]");
    EXPECT_EQ(r.fidelity, "variant");
    EXPECT_TRUE(r.notFaithful());
    EXPECT_EQ(r.provenanceText,
              "technique pcf: faithful, Reeves 1987\nbias=x: variant, paper\n  - one");
    j["provenance"]["parts"] = 3;
    try {
        readResultRow(j, JsonReader("m.json"), "results[0]");
        FAIL() << "parts of the wrong type";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("results[0].provenance.parts"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace so::test
