// temporal=on|off and resolve (docs/techniques.md#temporal): the parameters of a filtering
// technique whose taps turn every frame (interleaved gradient noise over a Vogel disk, with the
// frame term Bevy and Godot 4 add; three.js r182+ turns its PCF taps per pixel only, never per
// frame, and accumulates nothing), and how its frames are resolved (resolves/resolve.h: none, taa
// as Bevy resolves its lit image, history: a per-light history, the ideal upper bound). Shared by
// pcf, pcss and smrt, as SlopeBias is.
#pragma once

#include <memory>
#include <string>

#include "raster_compare/gl/params.h"
#include "raster_compare/gl/resolves/resolve.h"

namespace so {

struct TemporalTaps {
    // temporal (off, on); resolve (none, taa, history: the resolve axis, needs temporal=on) and
    // its plug-ins' parameters (history, clamp: resolve=history).
    static ParamTable params();
    explicit TemporalTaps(const ParamValues& values);
    // "#define TEMPORAL\n" when on (shaders/taps.glsl's tapRotation), else nothing: off
    // compiles the very shader it did before.
    std::string defines() const;
    // The resolve when on (Technique::resolve); null otherwise.
    const Resolve* resolve() const { return resolve_.get(); }

    bool on = false;

  private:
    std::unique_ptr<const Resolve> resolve_;
};

}  // namespace so
