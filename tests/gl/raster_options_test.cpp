// The raster option table's values written into RasterOptions
// (raster_compare/gl/render/raster_options.h): every row has its setter, each writes its own field,
// and RasterOptions{} holds the rows' defaults. No GL.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "raster_compare/gl/render/raster_options.h"

namespace so {
namespace {

TEST(RasterOptionTable, EveryRowHasItsSetterAndTheStructTheDefaults) {
    std::vector<std::string> keys;
    for (const OptionSpec& s : rasterOptionTable().rows) keys.push_back(s.key);
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(appliedRasterOptionKeys(), keys);
    const RasterOptions defaults;
    RasterOptions fromTable;
    fromTable.frames = fromTable.warmup = -1;
    for (const OptionSpec& s : rasterOptionTable().rows)
        applyRasterOptions({{s.key, s.defaultValue}}, {"t", false, "", false}, fromTable);
    EXPECT_EQ(fromTable.frames, defaults.frames);
    EXPECT_EQ(fromTable.warmup, defaults.warmup);
    // Each row's setter writes its own field: its maximum changes the options.
    for (const OptionSpec& s : rasterOptionTable().rows) {
        RasterOptions o;
        applyRasterOptions({{s.key, {s.max, ""}}}, {"t", false, "", false}, o);
        EXPECT_TRUE(o.frames != defaults.frames || o.warmup != defaults.warmup) << s.key;
    }
}

TEST(RasterOptionTable, AppliedValuesAreCheckedByTheRows) {
    RasterOptions o;
    try {
        applyRasterOptions({{"frames", {0, ""}}}, {"render options", false, "", false}, o);
        ADD_FAILURE() << "frames 0 accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "render options: frames: must be an integer in [1, 1000], got 0");
    }
    EXPECT_EQ(o.frames, RasterOptions{}.frames) << "nothing written before the check";
}

}  // namespace
}  // namespace so
