// The depth bias as an axis of plug-ins (issue 62), without GL: every biases/*.cpp file is a
// registered bias; every plain-map filter takes every bias by name, each bias's parameters only
// with it; the bias techniques are names for basic with a bias, their old parameter names kept.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

TEST(BiasRegistry, EveryBiasFileIsRegistered) {
    // SO_BIAS_FILE_COUNT: the biases/*.cpp files CMake saw (tests/CMakeLists.txt).
    EXPECT_EQ(kBuiltInBiasCount, size_t(SO_BIAS_FILE_COUNT))
        << "a biases/*.cpp file without exactly one SO_REGISTER_BIAS line at the start of a line";
    std::set<std::string> names;
    for (const BiasInfo& b : allBiases()) EXPECT_TRUE(names.insert(b.name).second) << b.name;
    EXPECT_EQ(names.size(), kBuiltInBiasCount);
    EXPECT_EQ(allBiases().front().name, "none");
    // Numbers are the biases' own (kNumber), fixed once given: bias=2 is slope for good.
    for (size_t i = 0; i < allBiases().size(); ++i) EXPECT_EQ(allBiases()[i].number, int(i));
    EXPECT_EQ(biasName(createTechnique("pcf", {"bias=2"})->values()), "slope");
    EXPECT_EQ(biasName(createTechnique("pcf", {"bias=0"})->values()), "none");
    BiasRegistry twice;
    registerBuiltInBiases(twice);
    EXPECT_THROW(registerBuiltInBiases(twice), std::invalid_argument);
}

TEST(BiasAxis, EveryFilterTakesEveryBiasAndOnlyItsParameters) {
    for (const char* filter :
         {"basic", "pcf", "hw-pcf", "pcss", "vsm", "esm", "evsm", "msm", "cascades"})
        for (const BiasInfo& b : allBiases()) {
            const std::unique_ptr<Technique> t = createTechnique(filter, {"bias=" + b.name});
            // The chosen bias's parameters are the values' (with their defaults); another's not.
            for (const ParamSpec& s : b.params) EXPECT_NO_THROW(t->values().real(s.name)) << filter;
            EXPECT_EQ(biasName(t->values()), b.name);
        }
    // A parameter of a bias not chosen is an error naming it, not silently ignored.
    EXPECT_THROW(createTechnique("pcf", {"bias=receiver-plane", "slope_factor=2"}), InputError);
    EXPECT_THROW(createTechnique("vsm", {"epsilon=3"}), InputError);  // vsm's default: none
    EXPECT_NO_THROW(createTechnique("vsm", {"bias=half-texel", "epsilon=3"}));
    // receiver-plane (issue 63: Isidoro's form, MJP's margin) and texel-plane (the texel-centre
    // form it had before) share the depth-precision epsilon; the margin is receiver-plane's alone.
    EXPECT_NO_THROW(createTechnique("pcf", {"bias=receiver-plane", "epsilon=3"}));
    EXPECT_NO_THROW(createTechnique("pcf", {"bias=texel-plane", "epsilon=3"}));
    const std::unique_ptr<Technique> rp = createTechnique("pcss", {"bias=receiver-plane"});
    EXPECT_EQ(rp->values().real("margin_texels"), 1.0);  // Mesh.hlsl:131
    EXPECT_EQ(rp->values().real("margin_cap"), 1.0);     // uncapped (Mesh.hlsl:132: 0.01)
    EXPECT_THROW(createTechnique("pcf", {"bias=texel-plane", "margin_cap=0.1"}), InputError);
    // The numbers are fixed: 6 stays receiver-plane, 8 the renamed half-texel, 9 texel-plane.
    EXPECT_EQ(biasName(createTechnique("pcf", {"bias=6"})->values()), "receiver-plane");
    EXPECT_EQ(biasName(createTechnique("pcf", {"bias=8"})->values()), "half-texel");
    EXPECT_EQ(biasName(createTechnique("pcf", {"bias=9"})->values()), "texel-plane");
    // `oriented` claimed a talk nobody read: renamed half-texel; the old value is still accepted,
    // with a notice, until format 8; the old technique name is an error that names the new one.
    const std::unique_ptr<Technique> old = createTechnique("pcf", {"bias=oriented"});
    EXPECT_EQ(biasName(old->values()), "half-texel");
    ASSERT_EQ(old->values().deprecations().size(), 1u);
    EXPECT_NE(old->values().deprecations()[0].find("half-texel"), std::string::npos);
    try {
        createTechnique("oriented-bias", {});
        FAIL() << "oriented-bias accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("half-texel-bias"), std::string::npos) << e.what();
    }
    EXPECT_THROW(createTechnique("pcf", {"bias=no-such-bias"}), InputError);
    // Unchosen biases' parameters are left out of the values (raster.json, metrics.json).
    const std::unique_ptr<Technique> pcf = createTechnique("pcf", {});
    EXPECT_EQ(pcf->values().all().count("epsilon"), 0u);
    EXPECT_EQ(pcf->values().all().count("slope_factor"), 1u);
}

TEST(BiasAxis, BiasTechniquesAreNamesForBasicWithABias) {
    const std::map<std::string, std::string> expansions = {
        {"bias", "basic:bias=constant"},
        {"slope-bias", "basic:bias=slope"},
        {"normal-offset", "basic:bias=normal-offset"},
        {"polygon-offset", "basic:bias=polygon-offset"},
        {"back-faces", "basic:bias=back-faces"},
        {"receiver-plane", "basic:bias=receiver-plane"},
        {"adaptive-bias", "basic:bias=adaptive"},
        {"half-texel-bias", "basic:bias=half-texel"}};
    for (const auto& [name, expansion] : expansions) {
        const TechniqueInfo& info = findTechnique(name);
        EXPECT_EQ(aliasExpansion(info), expansion);
        EXPECT_EQ(info.family, "shadow map");
        // The fixed bias is no parameter of the alias (a `bias` it lists is an old amount's name).
        for (const ParamSpec& s : info.params)
            if (s.name == "bias") {
                EXPECT_TRUE(s.names.empty()) << name << ": the axis is fixed";
            }
        EXPECT_EQ(createTechnique(name, {})->name(), name);
    }
    // The old names of their parameters are their tables' and their values' (raster.json and
    // metrics.json list them so), and reach the target under its names (the rendered check:
    // tests/cli/bias_axis_cli_test.cpp).
    const std::unique_ptr<Technique> bias = createTechnique("bias", {"bias=2.5"});
    EXPECT_EQ(bias->values().real("bias"), 2.5);
    EXPECT_EQ(bias->values().all().count("depth_texels"), 0u);
    const std::unique_ptr<Technique> normal = createTechnique("normal-offset", {"k=3", "bias=0.5"});
    EXPECT_EQ(normal->values().real("k"), 3.0);
    EXPECT_EQ(normal->values().real("bias"), 0.5);
    EXPECT_EQ(createTechnique("back-faces", {"bias=1"})->values().real("bias"), 1.0);
    // The slope factor's former name, alpha (left to alpha masks), still runs, with its notice.
    const std::unique_ptr<Technique> old = createTechnique("slope-bias", {"alpha=2"});
    EXPECT_EQ(old->values().real("slope_factor"), 2.0);
    ASSERT_EQ(old->values().deprecations().size(), 1u);
    EXPECT_NE(old->values().deprecations()[0].find("slope_factor"), std::string::npos);
    EXPECT_EQ(createTechnique("pcf", {"alpha=3"})->values().real("slope_factor"), 3.0);
    // The fixed bias is no parameter of the alias, nor another bias's parameters.
    EXPECT_THROW(createTechnique("slope-bias", {"bias=constant"}), InputError);
    EXPECT_THROW(createTechnique("receiver-plane", {"min=2"}), InputError);
    EXPECT_THROW(createTechnique("no-such", {}), InputError);
}

}  // namespace
}  // namespace so
