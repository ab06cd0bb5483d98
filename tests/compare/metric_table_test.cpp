// The metric table (raster_compare/compare/metric_table.h) against what the code writes: every
// name a full row of metrics.json has is in the table and every entry is in some row, so the two
// cannot drift; where a metric applies; docs/metrics.md's generated table; the gate's limit names.
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "raster_compare/compare/artifacts.h"
#include "raster_compare/compare/baseline.h"
#include "raster_compare/compare/gate.h"
#include "raster_compare/compare/metric_table.h"
#include "raster_compare/compare/metrics.h"

namespace so {
namespace {

using nlohmann::json;
namespace ch = channels;

// A row of metrics.json with every optional metric present: `hard` has the hard light's
// aliasing_rate, otherwise the area light's penumbra metrics; both have what needs a channel
// (occ_dist, aliasing_pred), a filtered technique's bleeding, costs and a camera path.
json fullRow(bool hard) {
    LightComparison l;
    LightMetrics& m = l.metrics;
    m.peterPanningRate = 0.1;
    m.lightLeakDistance = 0.2;
    m.boundaryBandMae = 0.3;
    m.lightBleedingRate = 0.4;
    m.predictedAliasingMean = 1.5;
    m.aliasingCorrelation = 0.6;
    if (hard) {
        m.aliasingRate = 0.05;
    } else {
        m.penumbraMae = m.penumbraBias = m.umbraMae = m.litMae = 0.01;
        m.penumbraWidth = PenumbraWidthError{1.0, 2.0, 3.0, 40};
    }
    const TimingStats t{1.0, 0.9, 1.1};
    l.cost.shadowMapMs = l.cost.visibilityMs = l.cost.cameraMs = l.cost.frameMs = t;
    l.cost.memoryBytes = 1024;
    l.cost.bakeMs = 250.0;
    l.cost.work = WorkCounts{100, 200, 300, 400, 5, 2};
    if (!hard) l.cost.oracleMsAtEqualError = 50.0;
    l.temporal = TemporalFlicker{};
    l.temporal->add({100, 3});
    l.sequence = SequenceMetrics{};
    l.sequence->maePerFrame = {0.1, 0.2};
    l.sequence->flicker.add({100, 3});
    l.sequence->lagPixels = 10;
    l.sequence->lagAbsSum = 2.0;
    return l.toJson();
}

TEST(MetricTable, EveryNameOfAFullRowIsInTheTableAndEveryEntryInARow) {
    std::set<std::string> written;
    for (bool hard : {true, false})
        for (const auto& [name, value] : flatMetrics(fullRow(hard))) {
            // A group none of whose members applies is one null (penumbra_width_error_px on a
            // hard light), as docs/metrics.md says.
            if (value.is_null() && isMetricGroup(name)) continue;
            EXPECT_NE(findMetric(name), nullptr) << name << " is written but not in the table";
            written.insert(name);
        }
    for (const MetricInfo& m : allMetrics())
        EXPECT_TRUE(written.count(m.name)) << m.name << " is in the table but in no row";
    // Names are unique, and every group is a prefix only (never a metric itself).
    std::set<std::string> seen;
    for (const MetricInfo& m : allMetrics()) {
        EXPECT_TRUE(seen.insert(m.name).second) << m.name << " twice";
        EXPECT_FALSE(isMetricGroup(m.name)) << m.name;
        EXPECT_FALSE(std::string(m.description).empty()) << m.name;
    }
}

// The reports show every metric by its row: a label no other metric shows, and a value formatted
// from the row's unit (compare's report, the index and the sweep report read nothing else).
TEST(MetricTable, ReportsShowAMetricAsItsRowSays) {
    std::map<std::string, std::string> shownBy;
    for (const MetricInfo& m : allMetrics()) {
        const std::string label = metricLabel(m);
        EXPECT_FALSE(label.empty()) << m.name;
        const auto [it, fresh] = shownBy.emplace(label, m.name);
        EXPECT_TRUE(fresh) << m.name << " and " << it->second << " are both shown as " << label;
    }
    EXPECT_EQ(metricLabel(*findMetric("acne_rate")), "acne");
    EXPECT_EQ(metricLabel(*findMetric("rmse")), "rmse") << "no label: the name";
    EXPECT_EQ(formatMetricValue(*findMetric("mae"), 0.25), "0.2500");
    EXPECT_EQ(formatMetricValue(*findMetric("penumbra_bias"), -0.0234), "-0.023");
    EXPECT_EQ(formatMetricValue(*findMetric("acne_rate"), 0.0123), "1.23%");
    EXPECT_EQ(formatMetricValue(*findMetric("cost.frame_ms"), 12.34), "12.3");
    EXPECT_EQ(formatMetricValue(*findMetric("cost.memory_bytes"), 3.0 * 1048576.0), "3.00");
    EXPECT_STREQ(displayUnit(*findMetric("cost.memory_bytes")), "MiB");
    EXPECT_EQ(displayScale(*findMetric("cost.memory_bytes")), 1.0 / 1048576.0);
    EXPECT_EQ(formatMetricValue(*findMetric("cost.work.fragments"), 2.5e6), "2.5 M");
    EXPECT_EQ(formatMetricValue(*findMetric("cost.noisy"), 1.0), "true");
}

// The report's error maps and the sweep's heat maps and fronts mark the lowest value of mae and
// of each artifact class's metric as the best: the table must agree.
TEST(MetricTable, TheArtifactMetricsAreLowerIsBetter) {
    EXPECT_EQ(findMetric("mae")->better, Better::Lower);
    for (const ArtifactClass& c : kArtifactClasses) {
        ASSERT_NE(findMetric(c.metric), nullptr) << c.metric;
        EXPECT_EQ(findMetric(c.metric)->better, Better::Lower) << c.metric;
    }
}

// Every pixel hits one triangle facing the light; the left half is in shadow in both images.
ChannelImage halfShadowed(bool area) {
    ChannelImage img(32, 16);
    img.addChannel(ch::kHit, 1.0f);
    img.addChannel(ch::kMeshId, 0.0f);
    img.addChannel(ch::kPrimId, 0.0f);
    img.addChannel(ch::lightChannel("L", ch::kVisibility), 1.0f);
    img.addChannel(ch::lightChannel("L", ch::kCosine), 1.0f);
    if (area) img.addChannel(ch::lightChannel("L", ch::kStdErr), 0.0f);
    float* v = img.channel(ch::lightChannel("L", ch::kVisibility));
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) v[size_t(y) * 32 + size_t(x)] = 0.0f;
    return img;
}

// computeLightMetrics without the optional channels and options: a metric the table scopes to
// something this row lacks is null or absent, as docs/metrics.md says.
TEST(MetricTable, MetricsOutsideTheirScopeAreNull) {
    for (bool area : {false, true}) {
        const ChannelImage o = halfShadowed(area), r = halfShadowed(false);
        LightComparison l;
        l.metrics = computeLightMetrics(o, r, "L", {});
        std::map<std::string, json> flat;
        for (auto& [name, value] : flatMetrics(l.toJson())) flat[name] = value;
        for (const MetricInfo& m : allMetrics()) {
            const MetricScope own = area ? MetricScope::AreaLights : MetricScope::HardLights;
            if (m.scope == MetricScope::All || m.scope == own) continue;
            const auto it = flat.find(m.name);
            EXPECT_TRUE(it == flat.end() || it->second.is_null())
                << m.name << " (" << scopeName(m.scope) << ") on " << (area ? "area" : "hard");
        }
    }
}

// The baseline compares only metrics that have a better direction.
TEST(MetricTable, TheBaselineComparesMetricsWithADirection) {
    for (const MetricInfo* b : baselineMetricTable()) EXPECT_NE(b->better, Better::None) << b->name;
    EXPECT_EQ(findMetric("penumbra_bias")->better, Better::SmallerMagnitude);
}

// docs/metrics.md's table is generated from the table: the document says what the gate checks.
TEST(MetricTable, DocMatchesTheCode) {
    std::ifstream in(std::filesystem::path(SO_DOCS_DIR) / "metrics.md", std::ios::binary);
    std::stringstream doc;
    doc << in.rdbuf();
    const std::string text = doc.str();
    const std::string begin = "<!-- BEGIN metric-table (generated: scripts/update-docs) -->\n\n",
                      end = "<!-- END metric-table -->";
    const size_t a = text.find(begin), b = text.find(end);
    ASSERT_NE(a, std::string::npos) << "docs/metrics.md lacks its metric-table markers";
    ASSERT_NE(b, std::string::npos) << "docs/metrics.md lacks its metric-table markers";
    EXPECT_EQ(text.substr(a + begin.size(), b - a - begin.size()), metricTableMarkdown())
        << "docs/metrics.md is stale: run scripts/update-docs";
}

json oneRun() {
    return {{"schema_version", kMetricsSchemaVersion},
            {"scene", {{"file", "scenes/box.scene.json"}}},
            {"results", json::array({{{"label", "a"}, {"lights", {{"l", fullRow(true)}}}}})}};
}

std::string gateError(const json& limits) {
    try {
        evaluateGate(oneRun(), "metrics.json", limits, "limits.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(MetricTable, TheGateRejectsAnUnknownLimitNamingTheNearestMetrics) {
    const std::string typo =
        gateError(json::parse(R"({"limits_format": 1, "default": {"acne_rat": 0.1}})"));
    EXPECT_EQ(typo.find('\n'), std::string::npos) << typo;
    EXPECT_NE(typo.find("limits.json"), std::string::npos) << typo;
    EXPECT_NE(typo.find("default.acne_rat: unknown metric (did you mean acne_rate"),
              std::string::npos)
        << typo;
    // A group is not a metric: its members are suggested.
    const std::string group = gateError(json::parse(
        R"({"limits_format": 1, "rules": [{"max": {"boundary_displacement_px": 1}}]})"));
    EXPECT_NE(group.find("rules[0].max.boundary_displacement_px: unknown metric (did you mean "
                         "boundary_displacement_px.mean, boundary_displacement_px.p95"),
              std::string::npos)
        << group;
    EXPECT_NE(gateError(json::parse(R"({"limits_format": 1, "default": {"zzz": 1}})"))
                  .find("zzz: unknown metric (see docs/metrics.md"),
              std::string::npos);
    // Every name in the table is a valid limit, whether or not this run has it (a camera path's
    // metrics, a hard light's row without the penumbra's): not applicable there.
    json all = json::object();
    for (const MetricInfo& m : allMetrics()) all[m.name] = 1e9;
    EXPECT_EQ(gateError({{"limits_format", 1}, {"default", all}}), "");
}

}  // namespace
}  // namespace so
