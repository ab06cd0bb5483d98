// Provenance on every technique, plug-in and named method value (issue 63), without GL: each has
// an anchor and a fidelity, a variant lists its deviations; an alias's is its target's and its
// bias's; a setting's parts are its technique's and the designs its chosen values name; the
// listing carries them (techniques --json format 7); and the former names announced "until
// format N" are still accepted by this format, so the next bump that reaches N must remove them.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/gl/technique_listing.h"

namespace so {
namespace {

TEST(Provenance, EveryTechniquePluginAndNamedValueHasOne) {
    for (const TechniqueInfo* t : allTechniques()) {
        EXPECT_NO_THROW(checkProvenance(t->provenance, "technique " + t->name));
        for (const ParamSpec& p : t->params) {
            if (p.provenances.empty()) continue;
            EXPECT_EQ(p.provenances.size(), p.names.size()) << t->name << " " << p.name;
            for (size_t k = 0; k < p.provenances.size(); ++k)
                EXPECT_NO_THROW(
                    checkProvenance(p.provenances[k], t->name + " " + p.name + "=" + p.names[k]));
        }
    }
    for (const PluginAxis& axis : registeredAxes())
        for (const AxisPlugin& p : axis.plugins)
            EXPECT_NO_THROW(checkProvenance(p.provenance, axis.name + " " + p.name));
}

TEST(Provenance, CheckCatchesMissingAnchorsAndDeviations) {
    EXPECT_THROW(checkProvenance({"", Fidelity::Own}, "x"), std::invalid_argument);
    EXPECT_THROW(checkProvenance({"a", Fidelity::Variant}, "x"), std::invalid_argument);
    EXPECT_THROW(checkProvenance({"a", Fidelity::Faithful, {"d"}}, "x"), std::invalid_argument);
    EXPECT_NO_THROW(checkProvenance({"a", Fidelity::Variant, {"d"}}, "x"));
}

TEST(Provenance, CombinedIsTheFarthestFromItsSources) {
    const ProvenancePart faithful{"technique basic", {"Williams 1978", Fidelity::Faithful}};
    const ProvenancePart variant{"bias=b", {"paper", Fidelity::Variant, {"one", "two"}}};
    const ProvenancePart own{"pattern=p", {"ours", Fidelity::Own}};
    EXPECT_EQ(combinedFidelity({}), Fidelity::Faithful);
    EXPECT_EQ(combinedFidelity({faithful}), Fidelity::Faithful);
    EXPECT_EQ(combinedFidelity({faithful, variant}), Fidelity::Variant);
    EXPECT_EQ(combinedFidelity({variant, own, faithful}), Fidelity::Own);
    const Provenance v = combinedProvenance({faithful, variant});
    EXPECT_EQ(v.anchor, "technique basic: Williams 1978; bias=b: paper");
    EXPECT_EQ(v.deviations, (std::vector<std::string>{"bias=b: one", "bias=b: two"}));
    EXPECT_NO_THROW(checkProvenance(v, "combined"));
    EXPECT_TRUE(combinedProvenance({faithful, variant, own}).deviations.empty());
}

// The parts name what was chosen: pcf with a bias has the bias's; an alias has its target's and
// its fixed bias's, and agrees with the same setting spelled out.
TEST(Provenance, ASettingsPartsAreItsTechniqueAndItsChosenDesigns) {
    const auto parts = provenanceParts(*createTechnique("pcf", {"bias=normal-offset"}));
    ASSERT_GE(parts.size(), 2u);
    EXPECT_EQ(parts[0].of, "technique pcf");
    bool bias = false;
    for (const ProvenancePart& p : parts) bias = bias || p.of == "bias=normal-offset";
    EXPECT_TRUE(bias);

    const auto alias = provenanceParts(*createTechnique("receiver-plane", {}));
    const auto spelled = provenanceParts(*createTechnique("basic", {"bias=receiver-plane"}));
    ASSERT_EQ(alias.size(), spelled.size());
    for (size_t i = 0; i < alias.size(); ++i) {
        EXPECT_EQ(alias[i].of, spelled[i].of);
        EXPECT_EQ(alias[i].provenance.anchor, spelled[i].provenance.anchor);
    }
    EXPECT_EQ(alias[0].of, "technique basic");
    const Provenance listed = findTechnique("receiver-plane").provenance;
    EXPECT_EQ(listed.anchor, combinedProvenance(alias).anchor);

    // The denoiser axis names the chosen denoiser.
    const auto rt = provenanceParts(*createTechnique("raytraced", {"denoiser=svgf"}));
    bool svgf = false;
    for (const ProvenancePart& p : rt) svgf = svgf || p.of == "denoiser=svgf";
    EXPECT_TRUE(svgf);
}

TEST(Provenance, ListedInTechniquesJson) {
    const nlohmann::json j = nlohmann::json::parse(techniquesListing(ListingFormat::Json));
    EXPECT_EQ(j["format_version"], kTechniquesJsonFormat);
    EXPECT_EQ(kTechniquesJsonFormat, 7);
    for (const nlohmann::json& t : j["techniques"]) {
        ASSERT_TRUE(t.contains("provenance")) << t["name"];
        const nlohmann::json& p = t["provenance"];
        EXPECT_FALSE(p["anchor"].get<std::string>().empty()) << t["name"];
        const std::string f = p["fidelity"];
        EXPECT_TRUE(f == "faithful" || f == "variant" || f == "own") << t["name"];
        EXPECT_EQ(p.contains("deviations"), f == "variant") << t["name"];
        if (f == "variant") {
            EXPECT_FALSE(p["deviations"].empty()) << t["name"];
        }
    }
    for (const auto& [name, axis] : j["axes"].items())
        for (const nlohmann::json& plugin : axis["plugins"]) {
            EXPECT_FALSE(plugin["provenance"]["anchor"].get<std::string>().empty())
                << name << " " << plugin["name"];
            EXPECT_TRUE(plugin["provenance"].contains("fidelity"));
        }
}

// A value's former name (`denoiser=penumbra`) is listed with what it now means.
TEST(Provenance, FormerValuesListed) {
    const nlohmann::json j = nlohmann::json::parse(techniquesListing(ListingFormat::Json));
    bool penumbra = false;
    for (const nlohmann::json& t : j["techniques"])
        if (t["name"] == "raytraced")
            for (const nlohmann::json& p : t["parameters"])
                if (p["name"] == "denoiser" && p.contains("former_values"))
                    for (const nlohmann::json& f : p["former_values"])
                        penumbra =
                            penumbra || (f["name"] == "penumbra" && f["current"] == "hitdist");
    EXPECT_TRUE(penumbra);
}

TEST(Provenance, FormerNamesOutliveThisFormat) {
    // A former name announced "accepted until format N" must still be accepted at every format
    // below N; when kTechniquesJsonFormat reaches N, this fails until the name is removed.
    for (const TechniqueInfo* t : allTechniques())
        for (const ParamSpec& p : t->params) {
            if (p.former) {
                EXPECT_GT(p.former->untilFormat, kTechniquesJsonFormat) << t->name << " " << p.name;
            }
            for (const FormerValue& f : p.formerValues)
                EXPECT_GT(f.untilFormat, kTechniquesJsonFormat) << t->name << " " << f.name;
        }
}

}  // namespace
}  // namespace so
