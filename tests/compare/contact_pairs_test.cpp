// The contact pairs (raster_compare/compare/contact_pairs.h): which settings pair, the signs of
// what contact=on closes and adds, and the sweep report's section with and without pairs.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "raster_compare/compare/contact_pairs.h"
#include "raster_compare/compare/result_row.h"
#include "raster_compare/compare/sweep_report.h"

namespace so::test {
namespace {

// A setting's row and its one light, as metrics.json is read back (result_row.h): `contact` a
// method (off 0, on 1), the other parameters numbers.
struct Setting {
    ResultRow row;
    LightRow light;
};

Setting setting(const std::string& label, const std::string& technique,
                std::map<std::string, double> parameters, std::optional<double> pp, double acne,
                std::optional<double> bleed, double falseShadow) {
    Setting s;
    s.row.label = label;
    s.row.technique = technique;
    for (const auto& [name, v] : parameters)
        s.row.parameters[name] = name == "contact"
                                     ? ParamValue{ParamValue::Kind::Name, v, v != 0 ? "on" : "off"}
                                     : ParamValue{ParamValue::Kind::Number, v, ""};
    s.light.light = "sun";
    s.light.set(metricInfo("peter_panning_rate"), pp);
    s.light.set(metricInfo("acne_rate"), acne);
    s.light.set(metricInfo("screen_bleed_rate"), bleed);
    s.light.set(metricInfo("false_shadow_rate"), falseShadow);
    return s;
}

std::vector<ContactPair> pairs(const std::vector<Setting>& s) {
    std::vector<ContactSetting> settings;
    for (const Setting& x : s) settings.push_back({&x.row, &x.light});
    return pairContactSettings(settings);
}

TEST(ContactPairs, PairsOnWithOffAtOtherwiseEqualSettings) {
    const std::vector<Setting> s = {
        setting("pcf", "pcf", {{"contact", 0}, {"resolution", 2048}}, 0.03, 0.001, {}, 0.01),
        setting("pcf:resolution=512", "pcf", {{"contact", 0}, {"resolution", 512}}, 0.05, 0, {},
                0.02),
        // contact_steps differs from the off row's default: the march's own settings do not count.
        setting("pcf:contact=on,contact_steps=8", "pcf",
                {{"contact", 1}, {"contact_steps", 8}, {"resolution", 2048}}, 0.01, 0.001, 0.004,
                0.014),
        // Same parameters, another technique: no off row of its own.
        setting("pcss:contact=on", "pcss", {{"contact", 1}, {"resolution", 2048}}, 0.0, 0, 0, 0),
        setting("raytraced", "raytraced", {{"spp", 1}}, 0.0, 0, {}, 0),
    };
    const std::vector<ContactPair> found = pairs(s);
    ASSERT_EQ(found.size(), 1u);
    const ContactPair& p = found[0];
    EXPECT_EQ(p.offLabel, "pcf");
    EXPECT_EQ(p.onLabel, "pcf:contact=on,contact_steps=8");
    EXPECT_NEAR(*p.peterPanningClosed(), 0.03 - 0.01, 1e-12);
    EXPECT_NEAR(*p.falseShadowAdded(), 0.014 - 0.01, 1e-12);
    EXPECT_NEAR(*p.screenBleedAdded(), 0.004, 1e-12);  // off: no screen-space pass, no bleed
    EXPECT_NEAR(*p.acneAdded(), 0.0, 1e-12);
}

TEST(ContactPairs, PeterPanningNotMeasuredStaysNull) {
    const std::vector<Setting> s = {
        setting("pcf", "pcf", {{"contact", 0}}, std::nullopt, 0, {}, 0),
        setting("pcf:contact=on", "pcf", {{"contact", 1}}, std::nullopt, 0, 0.001, 0.001)};
    const std::vector<ContactPair> found = pairs(s);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_FALSE(found[0].peterPanningClosed());
    std::ostringstream html;
    writeContactTable(html, found);
    EXPECT_NE(html.str().find("data-on=\"pcf:contact=on\""), std::string::npos);
    EXPECT_EQ(html.str().find("data-peter-panning-closed"), std::string::npos);
    std::ostringstream none;
    writeContactTable(none, {});
    EXPECT_TRUE(none.str().empty());
}

SweepRow sweepRow(const std::string& label, double contact, double pp, double resolution) {
    SweepRow r;
    r.task = "t-" + label;
    r.scene = "scenes/bunny.scene.json";
    const Setting s = setting(label, "pcf", {{"contact", contact}, {"resolution", resolution}}, pp,
                              0.0, std::nullopt, 0.01);
    r.result = s.row;
    r.result.lights = {s.light};
    r.swept = {{"contact", s.row.parameters.at("contact")}};
    return r;
}

std::string sweepPage(const std::vector<SweepRow>& rows) {
    SweepReportInput in;
    in.specFile = "contact.json";
    in.sweepName = "contact";
    in.rows = rows;
    in.tasks = rows.size();
    const std::filesystem::path path =
        std::filesystem::path(::testing::TempDir()) / "contact_pairs_sweep.html";
    writeSweepReport(path.string(), in);
    std::ifstream f(path);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

TEST(ContactPairs, SweepReportHasTheSectionOnlyWithPairs) {
    const std::string with = sweepPage(
        {sweepRow("pcf:contact=off", 0, 0.04, 2048), sweepRow("pcf:contact=on", 1, 0.01, 2048)});
    EXPECT_NE(with.find("<h3>Contact shadows</h3>"), std::string::npos);
    EXPECT_NE(with.find("data-peter-panning-closed=\"0.03\""), std::string::npos);
    // contact=on at another resolution than every contact=off: nothing to pair with.
    const std::string without = sweepPage(
        {sweepRow("pcf:contact=off", 0, 0.04, 2048), sweepRow("pcf:contact=on", 1, 0.01, 512)});
    EXPECT_EQ(without.find("Contact shadows"), std::string::npos);
}

}  // namespace
}  // namespace so::test
