// The gate against a baseline (raster_compare/compare/baseline.h, docs/gate.md#baseline) on
// synthetic metrics.json: better, worse within and beyond the tolerance, null on one side, rows
// missing either way, the oracle's noise, schema versions and the limits file's baseline object.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "raster_compare/compare/baseline.h"
#include "raster_compare/compare/gate.h"

namespace so {
namespace {

using nlohmann::json;

// A metrics.json of one scene; rows: label -> light -> metrics.
json run(const json& rows, int schema = 4, const json& oracleLights = json::array()) {
    json results = json::array();
    for (const auto& [label, lights] : rows.items())
        results.push_back({{"label", label}, {"technique", label}, {"lights", lights}});
    return {{"schema_version", schema},
            {"scene", {{"file", "scenes/box.scene.json"}}},
            {"oracle", {{"stats", {{"lights", oracleLights}}}}},
            {"results", results}};
}

const BaselineCheck* find(const BaselineComparison& b, const std::string& label,
                          const std::string& metric) {
    for (const BaselineCheck& c : b.checks)
        if (c.label == label && c.metric == metric) return &c;
    return nullptr;
}

BaselineComparison compare(const json& now, const json& old, const json* limits = nullptr) {
    return compareToBaseline(now, "new.json", old, "old.json", limits, "limits.json");
}

TEST(GateBaseline, BetterWorseWithinAndWorseBeyondTheTolerance) {
    // Defaults for a V metric: abs 0.001 + rel 5% of the baseline.
    const json old = run({{"a", {{"key", {{"mae", 0.1}, {"acne_rate", 0.02}, {"rmse", 0.2}}}}}});
    const json now = run({{"a", {{"key", {{"mae", 0.105}, {"acne_rate", 0.05}, {"rmse", 0.1}}}}}});
    const BaselineComparison b = compare(now, old);
    const BaselineCheck *mae = find(b, "a", "mae"), *acne = find(b, "a", "acne_rate"),
                        *rmse = find(b, "a", "rmse");
    ASSERT_TRUE(mae && acne && rmse);
    EXPECT_NEAR(mae->allowed(), 0.001 + 0.005, 1e-12);
    EXPECT_FALSE(mae->regressed());  // +0.005 within 0.006
    EXPECT_FALSE(mae->improved());
    EXPECT_TRUE(acne->regressed());  // +0.03 beyond 0.002
    EXPECT_TRUE(rmse->improved());
    EXPECT_FALSE(rmse->regressed());
    EXPECT_EQ(b.regressions(), 1u);
    EXPECT_TRUE(b.failed());
    // Unchanged: nothing fails, nothing improves.
    const BaselineComparison same = compare(old, old);
    EXPECT_FALSE(same.failed());
    for (const BaselineCheck& c : same.checks) EXPECT_FALSE(c.improved() || c.regressed());
    // Only quality metrics are compared by default: no counts, no costs.
    const json withCounts = run({{"a",
                                  {{"key",
                                    {{"mae", 0.1},
                                     {"counted_pixels", 10},
                                     {"cost", {{"frame_ms", 1.0}, {"memory_bytes", 5}}}}}}}});
    json more = withCounts;
    more["results"][0]["lights"]["key"]["counted_pixels"] = 99;
    more["results"][0]["lights"]["key"]["cost"]["frame_ms"] = 100.0;
    const BaselineComparison costs = compare(more, withCounts);
    EXPECT_FALSE(costs.failed());
    EXPECT_EQ(find(costs, "a", "counted_pixels"), nullptr);
    EXPECT_EQ(find(costs, "a", "cost.frame_ms"), nullptr);
}

TEST(GateBaseline, PenumbraBiasIsComparedByItsMagnitude) {
    const json old = run({{"flip", {{"l", {{"penumbra_bias", -0.1}}}}},
                          {"worse", {{"l", {{"penumbra_bias", -0.01}}}}},
                          {"better", {{"l", {{"penumbra_bias", 0.1}}}}}});
    const json now = run({{"flip", {{"l", {{"penumbra_bias", 0.1}}}}},
                          {"worse", {{"l", {{"penumbra_bias", -0.1}}}}},
                          {"better", {{"l", {{"penumbra_bias", 0.01}}}}}});
    const BaselineComparison b = compare(now, old);
    EXPECT_FALSE(find(b, "flip", "penumbra_bias")->regressed());
    EXPECT_FALSE(find(b, "flip", "penumbra_bias")->improved());
    EXPECT_TRUE(find(b, "worse", "penumbra_bias")->regressed());
    EXPECT_TRUE(find(b, "better", "penumbra_bias")->improved());
}

TEST(GateBaseline, NullOnOneSideIsNotApplicable) {
    const json old = run({{"a", {{"l", {{"penumbra_mae", nullptr}, {"mae", 0.1}}}}}});
    const json now = run({{"a", {{"l", {{"penumbra_mae", 0.9}, {"mae", nullptr}}}}}});
    const BaselineComparison b = compare(now, old);
    ASSERT_NE(find(b, "a", "penumbra_mae"), nullptr);
    EXPECT_FALSE(find(b, "a", "penumbra_mae")->applicable());
    EXPECT_FALSE(find(b, "a", "mae")->applicable());
    EXPECT_FALSE(b.failed());
    // A metric in neither run (temporal metrics without a camera path) is not listed at all.
    EXPECT_EQ(find(b, "a", "temporal_flicker_rate"), nullptr);
}

TEST(GateBaseline, ARowMissingInTheNewRunFailsANewRowPasses) {
    const json old = run({{"kept", {{"l", {{"mae", 0.1}}}}}, {"gone", {{"l", {{"mae", 0.1}}}}}});
    const json now = run({{"kept", {{"l", {{"mae", 0.1}}}}}, {"added", {{"l", {{"mae", 0.9}}}}}});
    const BaselineComparison b = compare(now, old);
    ASSERT_EQ(b.missing.size(), 1u);
    EXPECT_EQ(b.missing[0].label, "gone");
    EXPECT_EQ(b.missing[0].scene, "box.scene.json");
    ASSERT_EQ(b.added.size(), 1u);
    EXPECT_EQ(b.added[0].label, "added");
    EXPECT_EQ(b.regressions(), 0u);
    EXPECT_TRUE(b.failed());
    // Only a new row: passes.
    EXPECT_FALSE(compare(now, run({{"kept", {{"l", {{"mae", 0.1}}}}}})).failed());
    // Rows match by light too: the same label on another light is another row.
    const BaselineComparison lights =
        compare(run({{"kept", {{"m", {{"mae", 0.1}}}}}}), run({{"kept", {{"l", {{"mae", 0.1}}}}}}));
    EXPECT_EQ(lights.missing.size(), 1u);
    EXPECT_EQ(lights.added.size(), 1u);
}

TEST(GateBaseline, SchemaVersionsThatDefineMetricsDifferentlyAreAnInputError) {
    const json rows = {{"a", {{"l", {{"mae", 0.1}}}}}};
    EXPECT_NO_THROW(compare(run(rows, 5), run(rows, 4)));  // 5 adds rows, not definitions
    EXPECT_NO_THROW(compare(run(rows, 3), run(rows, 3)));
    try {
        compare(run(rows, 4), run(rows, 3));
        ADD_FAILURE() << "schema 3 against 4 accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "old.json");
        EXPECT_EQ(e.field(), "schema_version");
    }
    // 6 moves an area light's over-wide penumbra out of acne_rate: compared with itself only.
    EXPECT_NO_THROW(compare(run(rows, 6), run(rows, 6)));
    EXPECT_THROW(compare(run(rows, 6), run(rows, 5)), InputError);
    // 7 adds cost.work, no definitions: 6 and 7 compare.
    EXPECT_NO_THROW(compare(run(rows, 7), run(rows, 6)));
    EXPECT_THROW(compare(run(rows, 7), run(rows, 5)), InputError);
    EXPECT_THROW(compare(run(rows, 8), run(rows, 7)), InputError);
    // A label given twice: the n-th row matches the other run's n-th.
    json twice = run(rows);
    twice["results"].push_back(twice["results"][0]);
    twice["results"][1]["lights"]["l"]["mae"] = 0.5;
    json twiceLater = twice;
    twiceLater["results"][1]["lights"]["l"]["mae"] = 0.9;
    const BaselineComparison b = compare(twiceLater, twice);
    EXPECT_FALSE(find(b, "a", "mae")->regressed());
    ASSERT_NE(find(b, "a#2", "mae"), nullptr);
    EXPECT_TRUE(find(b, "a#2", "mae")->regressed());
    const BaselineComparison once = compare(run(rows), twice);
    ASSERT_EQ(once.missing.size(), 1u);
    EXPECT_EQ(once.missing[0].label, "a#2");
}

TEST(GateBaseline, AColdRowAgainstAConvergedOneIsAnInputError) {
    const json rows = {{"pcf:temporal=on", {{"l", {{"mae", 0.1}}}}},
                       {"pcf", {{"l", {{"mae", 0.1}}}}}};
    json cold = run(rows, 8), converged = run(rows, 8);
    cold["results"][1]["history_frames"] = 0;  // the rows are in label order: pcf, pcf:temporal=on
    converged["results"][1]["history_frames"] = 8;
    EXPECT_NO_THROW(compare(cold, cold));
    EXPECT_NO_THROW(compare(converged, converged));
    EXPECT_NO_THROW(compare(converged, run(rows, 8))) << "a baseline from before the key";
    try {
        compare(converged, cold);
        ADD_FAILURE() << "a converged row compared with a cold one";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "new.json");
        EXPECT_EQ(e.field(), "results[1].history_frames");
        EXPECT_NE(std::string(e.what()).find("8 for \"pcf:temporal=on\", 0 (a cold start) in the "
                                             "baseline old.json"),
                  std::string::npos)
            << e.what();
    }
}

TEST(GateBaseline, TheOracleNoiseOfBothRunsWidensAreaLightErrors) {
    // An area light whose oracle states a mean half-width of 0.01 over the penumbra in each run:
    // a V metric may move by hypot(0.01, 0.01) more; a share of pixels may not.
    const json lights =
        json::array({{{"name", "panel"},
                      {"worst_half_width", 0.02},
                      {"cost_curve", json::array({{{"penumbra_mean_half_width", 0.5}},
                                                  {{"penumbra_mean_half_width", 0.01}}})}},
                     {{"name", "sun"}}});
    const json oldRows = {
        {"a",
         {{"panel", {{"penumbra_mae", 0.05}, {"max_abs", 0.5}, {"acne_rate", 0.1}}},
          {"sun", {{"penumbra_mae", 0.05}}}}}};
    const json newRows = {
        {"a",
         {{"panel", {{"penumbra_mae", 0.065}, {"max_abs", 0.55}, {"acne_rate", 0.11}}},
          {"sun", {{"penumbra_mae", 0.065}}}}}};
    const BaselineComparison b = compare(run(newRows, 4, lights), run(oldRows, 4, lights));
    auto check = [&](const std::string& light, const std::string& metric) {
        for (const BaselineCheck& c : b.checks)
            if (c.light == light && c.metric == metric) return c;
        ADD_FAILURE() << light << " " << metric;
        return BaselineCheck{};
    };
    EXPECT_NEAR(check("panel", "penumbra_mae").noise, std::hypot(0.01, 0.01), 1e-12);
    EXPECT_FALSE(check("panel", "penumbra_mae").regressed());  // +0.015 < 0.0035 + 0.0141
    EXPECT_NEAR(check("panel", "max_abs").noise, std::hypot(0.02, 0.02), 1e-12);
    EXPECT_FALSE(check("panel", "max_abs").regressed());  // +0.05 < 0.001 + 0.025 + 0.028
    EXPECT_EQ(check("panel", "acne_rate").noise, 0.0);
    EXPECT_TRUE(check("panel", "acne_rate").regressed());
    // The hard light (no cost curve) has no noise: the same change regresses.
    EXPECT_EQ(check("sun", "penumbra_mae").noise, 0.0);
    EXPECT_TRUE(check("sun", "penumbra_mae").regressed());
    // Without the stats in one run, only the other run's uncertainty counts.
    const BaselineComparison one = compare(run(newRows, 4, lights), run(oldRows, 4));
    for (const BaselineCheck& c : one.checks)
        if (c.light == "panel" && c.metric == "penumbra_mae") {
            EXPECT_NEAR(c.noise, 0.01, 1e-12);
        }
    // A malformed stats entry is an InputError naming the field.
    json bad = run(oldRows, 4, json::array({{{"name", "panel"}, {"cost_curve", 3}}}));
    try {
        compare(run(newRows), bad);
        ADD_FAILURE() << "cost_curve 3 accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "oracle.stats.lights[0].cost_curve");
    }
}

TEST(GateBaseline, TheLimitsFileSetsTolerancesAndWhichMetricsAreCompared) {
    const json old = run({{"a",
                           {{"l",
                             {{"mae", 0.1},
                              {"acne_rate", 0.1},
                              {"boundary_displacement_px", {{"mean", 1.0}}},
                              {"cost", {{"frame_ms", 1.0}}}}}}}});
    const json now = run({{"a",
                           {{"l",
                             {{"mae", 0.2},
                              {"acne_rate", 0.15},
                              {"boundary_displacement_px", {{"mean", 1.2}}},
                              {"cost", {{"frame_ms", 3.0}}}}}}}});
    // Built-in: mae and acne regress, the displacement (+0.2 px < 0.25 + 5%) does not.
    const BaselineComparison builtIn = compare(now, old);
    EXPECT_TRUE(find(builtIn, "a", "mae")->regressed());
    EXPECT_TRUE(find(builtIn, "a", "acne_rate")->regressed());
    EXPECT_FALSE(find(builtIn, "a", "boundary_displacement_px.mean")->regressed());
    // default covers V and share metrics only; metrics names one (a cost: compared once named);
    // ignore drops one.
    const json limits = json::parse(R"({"limits_format": 2, "baseline": {
        "default": {"abs": 0.2, "rel": 0},
        "metrics": {"boundary_displacement_px.mean": {"abs": 0.1}, "cost.frame_ms": {"rel": 1}},
        "ignore": ["acne_rate"]}})");
    const BaselineComparison b = compare(now, old, &limits);
    EXPECT_FALSE(find(b, "a", "mae")->regressed());
    EXPECT_EQ(find(b, "a", "acne_rate"), nullptr);
    const BaselineCheck* d = find(b, "a", "boundary_displacement_px.mean");
    EXPECT_DOUBLE_EQ(d->tolerance.abs, 0.1);
    EXPECT_DOUBLE_EQ(d->tolerance.rel, 0.05);  // the built-in's, not default's
    EXPECT_TRUE(d->regressed());
    const BaselineCheck* cost = find(b, "a", "cost.frame_ms");
    ASSERT_NE(cost, nullptr);
    EXPECT_DOUBLE_EQ(cost->tolerance.abs, 0.5);
    EXPECT_TRUE(cost->regressed());  // +2 ms > 0.5 + 100% of 1 ms
    // The same file passes the limits reader (format 2); baseline needs format 2 and valid keys.
    EXPECT_NO_THROW(evaluateGate(now, "new.json", limits, "limits.json"));
    for (const char* bad :
         {R"({"limits_format": 1, "baseline": {}})",
          R"({"limits_format": 2, "baseline": {"metrics": {"counted_pixels": {"abs": 1}}}})",
          R"({"limits_format": 2, "baseline": {"metrics": {"mae": {"abs": -1}}}})",
          R"({"limits_format": 2, "baseline": {"metrics": {"mae": {"ab": 1}}}})",
          R"({"limits_format": 2, "baseline": {"default": 0.1}})",
          R"({"limits_format": 2, "baseline": {"ignore": ["mae"], "metrics": {"mae": {}}}})",
          R"({"limits_format": 2, "baseline": {"tolerance": {}}})", R"({"limits_format": 3})"}) {
        const json j = json::parse(bad);
        EXPECT_THROW(evaluateGate(now, "new.json", j, "limits.json"), InputError) << bad;
        if (j.contains("baseline")) {
            EXPECT_THROW(compare(now, old, &j), InputError) << bad;
        }
    }
}

}  // namespace
}  // namespace so
