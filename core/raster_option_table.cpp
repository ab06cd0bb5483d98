#include "core/raster_option_table.h"

#include <vector>

namespace so {

namespace {

constexpr double kMaxFrames = 1000;

// The rows, in the order of docs/cli.md. A default is stated once, by the constant a row uses.
std::vector<OptionSpec> makeTable() {
    std::vector<OptionSpec> t;
    t.push_back(integerOption(
        "frames", kDefaultFrames, 1, kMaxFrames,
        kSurfaceRaster | kSurfaceCompare | kSurfaceSweep | kSurfaceApi,
        "timed frames after the warm-up frames, median and quartiles reported; in compare the "
        "techniques take turns frame by frame",
        "timed frames per technique, after the warm-up frames; `frame_ms` is their median, with "
        "quartiles (raster.json, metrics.json); the techniques of one `compare` take turns frame "
        "by frame, so that background load falls on all alike"));
    t.push_back(integerOption("warmup", kDefaultWarmup, 0, kMaxFrames,
                              kSurfaceRaster | kSurfaceCompare | kSurfaceApi,
                              "untimed frames before the timed ones",
                              "untimed frames rendered before the timed ones (shader compilation, "
                              "first-use allocations)"));
    return t;
}

}  // namespace

const OptionTable& rasterOptionTable() {
    static const std::vector<OptionSpec> rows = makeTable();
    static const OptionTable table{"raster option", rows};
    return table;
}

const OptionSpec& rasterOption(const std::string& key) {
    return rasterOptionTable().at(key);
}

}  // namespace so
