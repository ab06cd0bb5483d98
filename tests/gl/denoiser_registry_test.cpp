// The ray-tracing family's denoisers as plug-ins (issue 62): every denoisers/*.cpp registration
// line is found, the numbers settings give stay fixed, the `raytraced` table is generated from the
// plug-ins' own tables (each parameter valid only with the denoisers that declare it), the listing
// carries the axis, and a parameter's former name (raytraced's and planar's `alpha`) is still
// accepted, converted, with one notice. No GL: label "technique".
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/gl/technique_listing.h"

namespace so {
namespace {

const ParamSpec* specOf(const ParamTable& table, const std::string& name) {
    for (const ParamSpec& p : table)
        if (p.name == name) return &p;
    return nullptr;
}

// The numbers are the values settings and rows gave before the names: fixed.
TEST(Denoisers, EveryFileIsRegisteredWithItsNumber) {
    EXPECT_EQ(kBuiltInDenoiserCount, 6u);
    const std::vector<std::string> expected = {"none", "temporal", "svgf", "ffx", "hitdist", "rtg"};
    ASSERT_EQ(allDenoisers().size(), expected.size());
    for (size_t k = 0; k < expected.size(); ++k) {
        EXPECT_EQ(allDenoisers()[k]->name, expected[k]);
        EXPECT_EQ(allDenoisers()[k]->number, int(k));
        EXPECT_FALSE(allDenoisers()[k]->summary.empty());
    }
    DenoiserRegistry again;
    registerBuiltInDenoisers(again);
    EXPECT_THROW(registerBuiltInDenoisers(again), std::invalid_argument);  // names taken
    DenoiserInfo copy = again.byNumber().at(2);
    copy.number = 9;
    EXPECT_THROW(again.add(copy), std::invalid_argument);  // "svgf" twice
}

// raytraced's table: spp, the denoiser by name, then each plug-in's parameters once, each needing
// the denoisers that declare it (the strings that were written by hand before issue 62).
TEST(Denoisers, RaytracedTableIsGeneratedFromThePlugins) {
    const ParamTable& table = findTechnique("raytraced").params;
    const ParamSpec* denoiser = specOf(table, "denoiser");
    ASSERT_NE(denoiser, nullptr);
    EXPECT_EQ(denoiser->names,
              (std::vector<std::string>{"none", "temporal", "svgf", "ffx", "hitdist", "rtg"}));
    EXPECT_EQ(specOf(table, "alpha"), nullptr);
    const std::vector<std::pair<std::string, std::string>> needs = {
        {"history", "denoiser=temporal|svgf|hitdist"},
        {"levels", "denoiser=svgf"},
        {"sigma_luminance", "denoiser=svgf"},
        {"sigma_normal", "denoiser=svgf|hitdist"},
        {"sigma_depth", "denoiser=svgf"},
        {"depth_similarity_sigma", "denoiser=ffx"},
        {"max_radius", "denoiser=hitdist"},
        {"radius_scale", "denoiser=hitdist"},
        {"taps", "denoiser=hitdist"},
        {"search_radius", "denoiser=hitdist"},
        {"variation_threshold", "denoiser=rtg"},
        {"max_variation", "denoiser=rtg"},
        {"sampling_matrix", "denoiser=rtg"}};
    ASSERT_EQ(table.size(), 2 + needs.size());
    for (size_t i = 0; i < needs.size(); ++i) {
        EXPECT_EQ(table[2 + i].name, needs[i].first);
        EXPECT_EQ(table[2 + i].needs, needs[i].second) << needs[i].first;
    }
    // history means what pcf's does: the history's weight.
    EXPECT_EQ(specOf(table, "history")->defaultValue, 0.8);
}

TEST(Denoisers, PluginsSharingANameMustAgree) {
    PluginAxis axis{"denoiser", kRayTracingFamily, "denoiser", {}};
    axis.plugins.push_back({"a", "first", {{"k", 1, 0, 2, false, "k"}}});
    axis.plugins.push_back({"b", "second", {{"k", 1, 0, 3, false, "k"}}});
    EXPECT_THROW(axisParams(axis), std::invalid_argument);
    axis.plugins[1].params[0].max = 2;
    const ParamTable merged = axisParams(axis);
    ASSERT_EQ(merged.size(), 1u);
    EXPECT_EQ(merged[0].needs, "denoiser=a|b");
    EXPECT_EQ(merged[0].doc, "a, b: k");
}

// A former name: converted, said once, both names at once an error, a converted value out of
// range named by the key that gave it.
TEST(FormerNames, RaytracedAlphaIsHistoryWithANotice) {
    const std::unique_ptr<Technique> old =
        createTechnique("raytraced", {"denoiser=svgf", "alpha=0.3"});
    const std::unique_ptr<Technique> now =
        createTechnique("raytraced", {"denoiser=svgf", "history=0.7"});
    EXPECT_EQ(old->values().real("history"), now->values().real("history"));
    EXPECT_EQ(old->values().all(), now->values().all());
    EXPECT_TRUE(now->values().deprecations().empty());
    ASSERT_EQ(old->values().deprecations().size(), 1u);
    EXPECT_EQ(old->values().deprecations()[0],
              "technique raytraced: `alpha` is deprecated, use `history` (history = 1 - alpha); "
              "accepted until format 8");
    EXPECT_THROW(createTechnique("raytraced", {"denoiser=svgf", "alpha=0.3", "history=0.7"}),
                 InputError);
    EXPECT_THROW(createTechnique("raytraced", {"denoiser=svgf", "history=0.7", "alpha=0.3"}),
                 InputError);
    // One key twice is no former name: the last holds, as before.
    const std::unique_ptr<Technique> twice =
        createTechnique("raytraced", {"denoiser=svgf", "alpha=0.3", "alpha=0.5"});
    EXPECT_EQ(twice->values().real("history"), 0.5);
    EXPECT_EQ(twice->values().deprecations().size(), 1u);
    EXPECT_EQ(createTechnique("pcf", {"kernel=3", "kernel=5"})->values().integer("kernel"), 5);
    EXPECT_THROW(createTechnique("raytraced", {"alpha=0.3"}), InputError);  // needs a denoiser
    try {
        createTechnique("raytraced", {"denoiser=temporal", "alpha=0.001"});
        ADD_FAILURE() << "alpha=0.001 gives history 0.999, beyond 0.99";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("alpha"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("history = 0.999"), std::string::npos) << e.what();
    }
}

// A former value name (issue 63): `denoiser=penumbra` is `hitdist` (its number, 4, unchanged),
// said once; an unknown name stays an error.
TEST(FormerNames, PenumbraDenoiserIsHitdistWithANotice) {
    const std::unique_ptr<Technique> old =
        createTechnique("raytraced", {"denoiser=penumbra", "taps=8"});
    const std::unique_ptr<Technique> now =
        createTechnique("raytraced", {"denoiser=hitdist", "taps=8"});
    EXPECT_EQ(old->values().all(), now->values().all());
    EXPECT_EQ(now->values().integer("denoiser"), 4);
    EXPECT_TRUE(now->values().deprecations().empty());
    ASSERT_EQ(old->values().deprecations().size(), 1u);
    EXPECT_EQ(old->values().deprecations()[0],
              "technique raytraced: `denoiser=penumbra` is deprecated, use `denoiser=hitdist`; "
              "accepted until format 8");
    const std::unique_ptr<Technique> byNumber =
        createTechnique("raytraced", {"denoiser=4", "taps=8"});
    EXPECT_EQ(byNumber->values().all(), now->values().all());
    EXPECT_TRUE(byNumber->values().deprecations().empty());
    EXPECT_THROW(createTechnique("raytraced", {"denoiser=umbra"}), InputError);
}

TEST(FormerNames, PlanarAlphaIsOpacityWithANotice) {
    const std::unique_ptr<Technique> old = createTechnique("planar", {"alpha=0.5"});
    EXPECT_EQ(old->values().real("opacity"), 0.5);
    ASSERT_EQ(old->values().deprecations().size(), 1u);
    EXPECT_EQ(old->values().deprecations()[0],
              "technique planar: `alpha` is deprecated, use `opacity`; accepted until format 8");
    EXPECT_EQ(specOf(findTechnique("planar").params, "alpha"), nullptr);
    EXPECT_NE(specOf(findTechnique("planar").params, "opacity"), nullptr);
}

// techniques --json: format 6, the denoiser axis with its plug-ins and their own tables, the
// renamed parameter's former name.
TEST(Denoisers, ListedAsAnAxis) {
    const nlohmann::json j = nlohmann::json::parse(techniquesListing(ListingFormat::Json));
    EXPECT_EQ(j["format_version"], 7);
    const nlohmann::json& axis = j["axes"]["denoiser"];
    EXPECT_EQ(axis["family"], findTechnique("raytraced").family);
    EXPECT_EQ(axis["parameter"], "denoiser");
    ASSERT_EQ(axis["plugins"].size(), 6u);
    EXPECT_EQ(axis["plugins"][0]["name"], "none");
    EXPECT_TRUE(axis["plugins"][0]["parameters"].empty());
    const nlohmann::json& svgf = axis["plugins"][2];
    EXPECT_EQ(svgf["name"], "svgf");
    std::vector<std::string> names;
    for (const auto& p : svgf["parameters"]) names.push_back(p["name"]);
    EXPECT_EQ(names, (std::vector<std::string>{"history", "levels", "sigma_luminance",
                                               "sigma_normal", "sigma_depth"}));
    EXPECT_EQ(svgf["parameters"][0]["former"]["name"], "alpha");
    EXPECT_EQ(svgf["parameters"][0]["former"]["until_format"], 8);
    const std::string text = techniquesListing(ListingFormat::Text);
    EXPECT_NE(text.find("denoiser plug-ins (ray tracing, denoiser=NAME)"), std::string::npos);
}

}  // namespace
}  // namespace so
