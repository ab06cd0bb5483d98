// temporal=on|off, resolve, history and clamp of pcf, pcss and smrt
// (raster_compare/gl/time/temporal_taps.h, resolves/resolve.h): which resolve the settings give
// Technique::resolve(), its passes and jitter, and the settings that are errors. No GL.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "raster_compare/gl/resolves/resolve.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

TEST(TemporalTaps, AResolveIsThereOnlyWithTemporalOnAndTaaIsTheDefault) {
    for (const char* technique : {"pcf", "pcss", "smrt"}) {
        SCOPED_TRACE(technique);
        EXPECT_EQ(createTechnique(technique, {})->resolve(), nullptr);
        EXPECT_EQ(createTechnique(technique, {"temporal=off"})->resolve(), nullptr);
        const auto on = createTechnique(technique, {"temporal=on"});
        ASSERT_NE(on->resolve(), nullptr);
        EXPECT_EQ(on->resolve()->name(), "taa");
        EXPECT_EQ(on->resolve()->passNames(), std::vector<std::string>{"taa"});
        for (const char* r : {"none", "taa", "history"})
            EXPECT_EQ(createTechnique(technique, {"temporal=on", std::string("resolve=") + r})
                          ->resolve()
                          ->name(),
                      r);
        EXPECT_TRUE(createTechnique(technique, {"temporal=on", "resolve=none"})
                        ->resolve()
                        ->passNames()
                        .empty());
        const auto history =
            createTechnique(technique, {"temporal=on", "resolve=history", "history=0.5"});
        EXPECT_EQ(history->values().real("history"), 0.5);
        EXPECT_EQ(history->resolve()->passNames(), std::vector<std::string>{"history"});
    }
    EXPECT_EQ(createTechnique("slope-bias", {})->resolve(), nullptr);  // the still-frame ones
}

// Bevy 0.19.1's jitter (taa/mod.rs:366-376): 8 Halton(2, 3) offsets from (0, 0), by frame % 8;
// the image moves by -offset, y down the screen. No jitter for the other resolves.
TEST(TemporalTaps, TaaJittersTheCameraAsBevyDoes) {
    const auto taa = createTechnique("pcf", {"temporal=on", "resolve=taa"});
    const Resolve& r = *taa->resolve();
    EXPECT_EQ(r.jitterPixels(0), glm::dvec2(0.0, 0.0));
    EXPECT_EQ(r.jitterPixels(1), glm::dvec2(-0.0, -1.0 / 6.0));
    EXPECT_EQ(r.jitterPixels(2), glm::dvec2(0.25, 1.0 / 6.0));
    EXPECT_EQ(r.jitterPixels(7), glm::dvec2(-0.375, 1.0 / 18.0));
    EXPECT_EQ(r.jitterPixels(9), r.jitterPixels(1));
    for (int f = 0; f < 8; ++f) {
        EXPECT_LE(std::abs(r.jitterPixels(f).x), 0.5);
        EXPECT_LE(std::abs(r.jitterPixels(f).y), 0.5);
    }
    for (const char* other : {"resolve=none", "resolve=history"})
        EXPECT_EQ(createTechnique("pcf", {"temporal=on", other})->resolve()->jitterPixels(3),
                  glm::dvec2(0.0));
}

// The error names the technique and the key, on one line.
void expectInputError(const std::string& technique, const std::vector<std::string>& settings,
                      const std::string& key) {
    try {
        createTechnique(technique, settings);
        ADD_FAILURE() << technique << ": no error for " << settings.back();
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "technique " + technique);
        EXPECT_EQ(e.field(), key);
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
}

TEST(TemporalTaps, BadSettingsAreInputErrors) {
    for (const char* technique : {"pcf", "pcss"}) {
        expectInputError(technique, {"temporal=on", "resolve=history", "history=1"}, "history");
        expectInputError(technique, {"temporal=on", "resolve=history", "history=-0.1"}, "history");
        expectInputError(technique, {"temporal=on", "resolve=history", "clamp=maybe"}, "clamp");
        expectInputError(technique, {"temporal=on", "resolve=blend"}, "resolve");
        // Without what they need they would silently do nothing.
        expectInputError(technique, {"clamp=on"}, "clamp");
        expectInputError(technique, {"temporal=off", "history=0.5"}, "history");
        expectInputError(technique, {"temporal=on", "history=0.5"}, "history");  // taa's
        expectInputError(technique, {"resolve=taa"}, "resolve");
    }
    EXPECT_NO_THROW(createTechnique("pcf", {"temporal=on", "resolve=history", "history=0.999"}));
}

}  // namespace
}  // namespace so
