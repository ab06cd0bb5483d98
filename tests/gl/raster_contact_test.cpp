// Screen-space contact shadows, contact=on of the shadow-map family with contact_method=bevy, bend
// or guarded (contact_shadows.h, docs/techniques.md#contact), on the Stanford bunny resting on a
// plane (issues 54, 63): they close the gap a map's bias opens where the bunny touches the ground
// (peter-panning) and add no acne, since the false shadows they do add are screen-space bleed: the
// map's own comparison lit those pixels. Label "gl".
//
// The measurement, at 512 x 384 (a minute or two on llvmpipe, the oracle's trace most of
// it): so_raster_tests --gtest_also_run_disabled_tests --gtest_filter='Contact.DISABLED_*'
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bunny_scene.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/lights/make_light.h"
#include "core/scene.h"
#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/gl/shadow_maps/contact_shadows.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

const char* const kMethods[] = {"bevy", "bend", "guarded"};

// The bunny under a sun and a spot, with occ_dist (the contact effect) for peter-panning.
Scene bunnyUnderSunAndSpot(const MeshPrimitive& bunny, int width, int height) {
    Scene s = makeBunnyScene(bunny, width, height);
    s.lights = {directionalLight("sun", glm::normalize(glm::dvec3(-0.5, -1.0, -0.375))),
                spotLight("spot", {7.0, 12.0, 9.0}, glm::dvec3(-7.0, -12.0, -9.0), 35.0, 30.0)};
    s.effects = {"hard", "contact"};
    finalizeScene(s);
    return s;
}

struct ContactRates {
    double peterPanning = 0.0, acne = 0.0, falseShadow = 0.0, screenBleed = 0.0;
};

// Per light, pcf's rates with `settings` added (none: contact=off), printed.
std::map<std::string, ContactRates> pcfRates(const Scene& s, const ChannelImage& oracle,
                                             const std::vector<std::string>& settings,
                                             const char* label) {
    MetricOptions options;
    options.contactThreshold = 0.01 * s.wsBounds.extent();  // compare's default
    const ChannelImage image = renderOneFrame(s, "pcf", settings, false).image;
    std::map<std::string, ContactRates> rates;
    for (const Light& l : s.lights) {
        const LightMetrics m = computeLightMetrics(oracle, image, l.name, options);
        EXPECT_TRUE(m.peterPanningRate.has_value()) << l.name;
        ContactRates& r = rates[l.name];
        r = {m.peterPanningRate.value_or(-1), m.acneRate, m.falseShadowRate,
             m.screenBleedRate.value_or(0)};
        std::printf(
            "[ contact ] bunny %dx%d %-4s %-20s peter-panning %.4f acne %.4f false "
            "shadow %.4f screen bleed %.4f\n",
            s.camera.width, s.camera.height, l.name.c_str(), label, r.peterPanning, r.acne,
            r.falseShadow, r.screenBleed);
    }
    return rates;
}

// pcf's rates per light, contact=off ("off") and each method; printed.
std::map<std::string, std::map<std::string, ContactRates>> measureBunny(int width, int height) {
    std::string why;
    const MeshPrimitive* bunny = cgalBunny(why);
    if (!bunny) return {};
    const Scene s = bunnyUnderSunAndSpot(*bunny, width, height);
    const ChannelImage oracle = runQuiet(s);
    std::map<std::string, std::map<std::string, ContactRates>> rates;
    rates["off"] = pcfRates(s, oracle, {}, "pcf");
    for (const char* method : kMethods) {
        const std::string m = std::string("contact_method=") + method;
        rates[method] = pcfRates(s, oracle, {"contact=on", m}, m.c_str() + 8);
    }
    return rates;
}

// The criterion: half of contact=off's peter-panning closed on every light, with at most
// 0.01 more acne.
bool closesHalf(const std::map<std::string, std::map<std::string, ContactRates>>& rates,
                const std::string& method) {
    bool ok = true;
    for (const auto& [light, off] : rates.at("off")) {
        const ContactRates& on = rates.at(method).at(light);
        EXPECT_GT(off.peterPanning, 0.0) << light << ": no gap to close";
        ok = ok && on.peterPanning <= 0.5 * off.peterPanning && on.acne <= off.acne + 0.01;
    }
    return ok;
}

// Every method's figures at a size llvmpipe renders in seconds (docs/techniques.md#contact gives
// them with the 512 x 384 ones). The criterion, half of pcf's peter-panning closed on the
// sun and on the spot with at most 0.01 more acne, holds here for guarded only (as at 512 x 384);
// bevy closes some of it (about half at 512 x 384), bend at most a little: on this bunny the gap is
// on its own curved surface, next to its self-shadows, where both engines' marches are built not
// to shadow.
TEST(Contact, OnlyGuardedClosesHalfThePeterPanningOnTheBunnyWithoutAcne) {
    REQUIRE_GL();
    std::string why;
    if (!cgalBunny(why)) GTEST_SKIP() << why;
    const std::map<std::string, std::map<std::string, ContactRates>> r = measureBunny(200, 150);
    for (const std::string light : {"sun", "spot"}) {
        const ContactRates& off = r.at("off").at(light);
        EXPECT_LT(r.at("bevy").at(light).peterPanning, off.peterPanning) << light;
        EXPECT_LE(r.at("bend").at(light).peterPanning, off.peterPanning) << light;
        for (const char* method : kMethods)
            EXPECT_LE(r.at(method).at(light).acne, off.acne + 0.01) << method << " " << light;
    }
    EXPECT_TRUE(closesHalf(r, "guarded"));
}

TEST(Contact, DISABLED_MeasureEveryMethodAt512x384) {
    REQUIRE_GL();
    std::string why;
    if (!cgalBunny(why)) GTEST_SKIP() << why;
    const auto rates = measureBunny(512, 384);
    for (const char* method : kMethods)
        std::printf("[ contact ] 512x384 %s closes half on both lights, acne +0.01 at most: %s\n",
                    method, closesHalf(rates, method) ? "yes" : "no");
}

// A box resting on the floor under a point light (scenes/contact_box), its map biased by 40 texels
// so that the shadow starts away from the box's base: every method closes that gap (the
// issue's half at least, in fact all of it at 160 x 120) and adds no acne. The bunny's gap above is
// of another kind.
TEST(Contact, EveryMethodClosesTheGapAtABoxsBase) {
    REQUIRE_GL();
    Scene s = loadScene(std::string(SO_SCENES_DIR) + "/contact_box.scene.json");
    s.camera.width = 160;
    s.camera.height = 120;
    const ChannelImage oracle = runQuiet(s);
    MetricOptions options;
    options.contactThreshold = 0.01 * s.wsBounds.extent();
    const auto rates = [&](const std::vector<std::string>& settings) {
        return computeLightMetrics(oracle, renderOneFrame(s, "bias", settings, false).image, "key",
                                   options);
    };
    const LightMetrics off = rates({"bias=40"});
    ASSERT_TRUE(off.peterPanningRate.has_value());
    EXPECT_GT(*off.peterPanningRate, 0.005) << "the bias opens a gap";
    for (const char* method : kMethods) {
        const LightMetrics on =
            rates({"bias=40", "contact=on", std::string("contact_method=") + method});
        std::printf("[ contact ] box 160x120 bias=40 %-8s peter-panning %.4f -> %.4f\n", method,
                    *off.peterPanningRate, on.peterPanningRate.value_or(-1));
        EXPECT_LE(on.peterPanningRate.value_or(1), 0.5 * *off.peterPanningRate) << method;
        EXPECT_LE(on.acneRate, off.acneRate + 0.01) << method;
    }
}

// A lone plane under a sun and a spot: nothing to cast a contact shadow, and neither depth-only
// method shadows the plane by its own depth (Bend's window starts in front of the ray; Bevy's
// ray rises above the plane it leaves): V is the map's, to float rounding.
TEST(Contact, ALonePlaneStaysLitUnderEveryMethod) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {24, 0, 0}, {0, 0, -24}, 4, "ground"));
    aimCamera(s, {-9.0, 8.0, 15.0}, {0.0, 0.0, 0.0}, 45.0, 64, 48);
    s.lights = {directionalLight("sun", glm::normalize(glm::dvec3(-0.5, -1.0, -0.375))),
                spotLight("spot", {7.0, 12.0, 9.0}, glm::dvec3(-7.0, -12.0, -9.0), 35.0, 30.0)};
    s.effects = {"hard"};
    finalizeScene(s);
    const ChannelImage off = renderOneFrame(s, "pcf", {}, false).image;
    for (const char* method : kMethods) {
        const ChannelImage on =
            renderOneFrame(s, "pcf", {"contact=on", std::string("contact_method=") + method}, false)
                .image;
        for (const Light& l : s.lights) {
            const std::string v = ch::lightChannel(l.name, ch::kVisibility);
            double worst = 0.0;
            for (size_t i = 0; i < off.pixelCount(); ++i)
                worst = std::max(worst, double(std::abs(on.channel(v)[i] - off.channel(v)[i])));
            EXPECT_LE(worst, 1e-6) << method << " " << l.name;
        }
    }
}

// contact=off is the shader it was: V bit for bit; the march's settings need it on, and each
// method's own settings need that method.
TEST(Contact, OffChangesNothingAndItsSettingsNeedIt) {
    REQUIRE_GL();
    const Scene s = makePenumbraScene(48, 36).scene;
    const ChannelImage a = renderOneFrame(s, "slope-bias", {}, false).image;
    const ChannelImage b = renderOneFrame(s, "slope-bias", {"contact=off"}, false).image;
    const std::string v = ch::lightChannel("panel", ch::kVisibility);
    EXPECT_EQ(0, std::memcmp(a.channel(v), b.channel(v), a.pixelCount() * sizeof(float)));
    EXPECT_FALSE(b.has(ch::lightChannel("panel", ch::kVisibilityUnfiltered)));
    EXPECT_THROW(createTechnique("pcf", {"contact_steps=8"}), InputError);
    EXPECT_THROW(createTechnique("pcf", {"contact_method=bend"}), InputError);
    EXPECT_THROW(createTechnique("pcf", {"contact_samples=30"}), InputError);  // needs on, too
    EXPECT_THROW(createTechnique("pcf", {"contact=on", "contact_samples=30"}), InputError);
    EXPECT_THROW(createTechnique("pcf", {"contact=on", "contact_method=bend", "contact_steps=8"}),
                 InputError);
    EXPECT_NO_THROW(createTechnique("pcf", {"contact=on", "contact_steps=8"}));  // bevy's
    EXPECT_NO_THROW(
        createTechnique("pcf", {"contact=on", "contact_method=guarded", "contact_thickness=0.2"}));
    EXPECT_NO_THROW(
        createTechnique("pcf", {"contact=on", "contact_method=bend", "contact_contrast=2"}));
}

// The names' provenance: bevy and bend are engines' designs (bevy a variant only in how it reads
// depth, bend in how its rays are shared), guarded is ours.
TEST(Contact, EachMethodNamesItsSource) {
    for (const ParamSpec& p : ContactShadows::params())
        if (p.name == "contact_method") {
            ASSERT_EQ(p.provenances.size(), p.names.size());
            EXPECT_EQ(p.names[size_t(p.defaultValue)], "bevy");
            EXPECT_EQ(p.provenances[0].fidelity, Fidelity::Variant);
            EXPECT_EQ(p.provenances[1].fidelity, Fidelity::Variant);
            EXPECT_EQ(p.provenances[2].fidelity, Fidelity::Own);
            for (const Provenance& pv : p.provenances) EXPECT_NO_THROW(checkProvenance(pv, p.name));
            return;
        }
    ADD_FAILURE() << "no contact_method";
}

}  // namespace
}  // namespace so::test
