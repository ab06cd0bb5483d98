// temporal=on|off, history and clamp of pcf and pcss (raster_compare/gl/time/temporal_taps.h): what
// the settings give Technique::history(), and the settings that are errors. No GL.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

TEST(TemporalTaps, HistoryIsThereOnlyWithTemporalOn) {
    for (const char* technique : {"pcf", "pcss"}) {
        EXPECT_FALSE(createTechnique(technique, {})->history()) << technique;
        EXPECT_FALSE(createTechnique(technique, {"temporal=off"})->history()) << technique;
        const auto defaults = createTechnique(technique, {"temporal=on"})->history();
        ASSERT_TRUE(defaults) << technique;
        EXPECT_EQ(defaults->weight, 0.9);
        EXPECT_TRUE(defaults->clamp);
        const auto set =
            createTechnique(technique, {"temporal=on", "history=0", "clamp=off"})->history();
        ASSERT_TRUE(set) << technique;
        EXPECT_EQ(set->weight, 0.0);
        EXPECT_FALSE(set->clamp);
    }
    EXPECT_FALSE(createTechnique("slope-bias", {})->history());  // the still-frame techniques
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
        expectInputError(technique, {"temporal=on", "history=1"}, "history");  // [0, 1)
        expectInputError(technique, {"temporal=on", "history=-0.1"}, "history");
        expectInputError(technique, {"temporal=on", "clamp=maybe"}, "clamp");
        // Without temporal=on they would silently do nothing.
        expectInputError(technique, {"clamp=on"}, "clamp");
        expectInputError(technique, {"temporal=off", "history=0.5"}, "history");
    }
    EXPECT_NO_THROW(createTechnique("pcf", {"temporal=on", "history=0.999"}));
}

}  // namespace
}  // namespace so
