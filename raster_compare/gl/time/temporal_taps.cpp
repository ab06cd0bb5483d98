#include "raster_compare/gl/time/temporal_taps.h"

#include <utility>

namespace so {

ParamTable TemporalTaps::params() {
    const PluginAxis axis = resolveAxis();
    std::string doc;
    for (const AxisPlugin& p : axis.plugins)
        doc += (doc.empty() ? "" : "; ") + p.name + ": " + p.summary;
    ParamSpec resolve = axisParam(
        axis, 1,
        "temporal=on: how the frames are resolved (" + doc + "; docs/techniques.md#resolve)");
    resolve.needs = "temporal=on";
    ParamTable table = {methodParam("temporal", 0, {"off", "on"},
                                    "on: the taps turn every frame (a Vogel disk rotated per "
                                    "pixel by interleaved gradient noise offset by the frame "
                                    "index), resolved over frames as `resolve` says "
                                    "(docs/techniques.md#temporal)"),
                        resolve};
    for (ParamSpec& p : axisParams(axis)) table.push_back(std::move(p));
    return table;
}

TemporalTaps::TemporalTaps(const ParamValues& v) : on(v.integer("temporal") == 1) {
    if (on) resolve_ = createResolve(v);
}

std::string TemporalTaps::defines() const {
    return on ? "#define TEMPORAL\n" : "";
}

}  // namespace so
