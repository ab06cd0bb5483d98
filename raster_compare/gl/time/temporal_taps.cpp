#include "raster_compare/gl/time/temporal_taps.h"

namespace so {

ParamTable TemporalTaps::params() {
    ParamSpec history = {"history",
                         0.9,
                         0.0,
                         1.0,
                         false,
                         "temporal=on: the history's weight in each resolved frame (exponential "
                         "blend); 0: the jitter alone, each frame on its own"};
    history.maxExclusive = true;
    history.needs = "temporal=on";
    ParamSpec clamp = methodParam("clamp", 1, {"off", "on"},
                                  "temporal=on: the history clamped to the current frame's 3x3 "
                                  "neighbourhood (against ghosting)");
    clamp.needs = "temporal=on";
    return {methodParam("temporal", 0, {"off", "on"},
                        "on: the taps turn every frame (a Vogel disk rotated per pixel by "
                        "interleaved gradient noise offset by the frame index), resolved by a "
                        "reprojected history (docs/techniques.md#temporal)"),
            history, clamp};
}

TemporalTaps::TemporalTaps(const ParamValues& v)
    : on(v.integer("temporal") == 1), settings{v.real("history"), v.integer("clamp") == 1} {}

std::string TemporalTaps::defines() const {
    return on ? "#define TEMPORAL\n" : "";
}

std::optional<HistorySettings> TemporalTaps::history() const {
    if (!on) return std::nullopt;
    return settings;
}

}  // namespace so
