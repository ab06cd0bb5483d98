// temporal=on|off, history and clamp (docs/techniques.md#temporal): the parameters of a filtering
// technique whose taps turn every frame (interleaved gradient noise over a Vogel disk, with the
// frame term Bevy and Godot 4 add; three.js r182+ turns its PCF taps per pixel only, never per
// frame, and accumulates nothing), its jittered V resolved over frames by a ShadowHistory: a
// resolve of our own, where Bevy and Godot leave it to a TAA of the lit image. Shared by pcf and
// pcss, as SlopeBias is.
#pragma once

#include <optional>
#include <string>

#include "raster_compare/gl/params.h"
#include "raster_compare/gl/time/shadow_history.h"

namespace so {

struct TemporalTaps {
    // temporal (off, on), history in [0, 1), clamp (off, on); history and clamp need temporal=on
    // (ParamSpec::needs: given with temporal=off, an InputError naming the technique and the key).
    static ParamTable params();
    explicit TemporalTaps(const ParamValues& values);
    // "#define TEMPORAL\n" when on (shaders/taps.glsl's tapRotation), else nothing: off
    // compiles the very shader it did before.
    std::string defines() const;
    // The history's settings when on; none otherwise (Technique::history).
    std::optional<HistorySettings> history() const;

    bool on = false;
    HistorySettings settings;
};

}  // namespace so
