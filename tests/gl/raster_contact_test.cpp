// Screen-space contact shadows, contact=on of the shadow-map family (contact_shadows.h,
// docs/techniques.md#contact), on the Stanford bunny resting on a plane (issue 54): they close the
// gap a map's bias opens where the bunny touches the ground (peter-panning) and add no acne, since
// the false shadows they do add are screen-space bleed: the map's own comparison lit those pixels.
// Label "gl".
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bunny_scene.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/lights/make_light.h"
#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

// The bunny under a sun and a spot, with occ_dist (the contact effect) for peter-panning.
Scene bunnyUnderSunAndSpot(const MeshPrimitive& bunny) {
    Scene s = makeBunnyScene(bunny, 200, 150);
    s.lights = {directionalLight("sun", glm::normalize(glm::dvec3(-0.5, -1.0, -0.375))),
                spotLight("spot", {7.0, 12.0, 9.0}, glm::dvec3(-7.0, -12.0, -9.0), 35.0, 30.0)};
    s.effects = {"hard", "contact"};
    finalizeScene(s);
    return s;
}

TEST(Contact, ClosesPeterPanningOnTheBunnyWithoutAcne) {
    REQUIRE_GL();
    std::string why;
    const MeshPrimitive* bunny = cgalBunny(why);
    if (!bunny) GTEST_SKIP() << why;
    const Scene s = bunnyUnderSunAndSpot(*bunny);
    const ChannelImage o = runQuiet(s);
    MetricOptions options;
    options.contactThreshold = 0.01 * s.wsBounds.extent();  // compare's default
    const ChannelImage plain = renderOneFrame(s, "pcf", {}, false).image;
    const ChannelImage contact = renderOneFrame(s, "pcf", {"contact=on"}, false).image;
    for (const Light& l : s.lights) {
        const LightMetrics a = computeLightMetrics(o, plain, l.name, options),
                           b = computeLightMetrics(o, contact, l.name, options);
        ASSERT_TRUE(a.peterPanningRate && b.peterPanningRate);
        ASSERT_TRUE(contact.has(ch::lightChannel(l.name, ch::kVisibilityUnfiltered)));
        std::printf(
            "[ contact ] bunny %-4s pcf: peter-panning %.4f acne %.4f false shadow %.4f; "
            "contact=on: peter-panning %.4f acne %.4f false shadow %.4f screen bleed %.4f\n",
            l.name.c_str(), *a.peterPanningRate, a.acneRate, a.falseShadowRate, *b.peterPanningRate,
            b.acneRate, b.falseShadowRate, b.screenBleedRate.value_or(-1));
        EXPECT_GT(*a.peterPanningRate, 0.0) << l.name << ": no gap to close";
        EXPECT_LE(*b.peterPanningRate, 0.5 * *a.peterPanningRate) << l.name;
        EXPECT_LE(b.acneRate, a.acneRate + 0.01) << l.name;
    }
}

// contact=off is the shader it was: V bit for bit; and the march's own settings need it on.
TEST(Contact, OffChangesNothingAndItsSettingsNeedIt) {
    REQUIRE_GL();
    const Scene s = makePenumbraScene(48, 36).scene;
    const ChannelImage a = renderOneFrame(s, "slope-bias", {}, false).image;
    const ChannelImage b = renderOneFrame(s, "slope-bias", {"contact=off"}, false).image;
    const std::string v = ch::lightChannel("panel", ch::kVisibility);
    EXPECT_EQ(0, std::memcmp(a.channel(v), b.channel(v), a.pixelCount() * sizeof(float)));
    EXPECT_FALSE(b.has(ch::lightChannel("panel", ch::kVisibilityUnfiltered)));
    EXPECT_THROW(createTechnique("pcf", {"contact_steps=8"}), InputError);
}

}  // namespace
}  // namespace so::test
