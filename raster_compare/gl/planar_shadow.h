// The planar-projection family: casters flattened onto a planar receiver from the light (Blinn
// 1988) and drawn over it. `planar` projects once; `plane-shift` (Gooch et al. 1999) averages the
// projections onto planes shifted towards the light, each flattened back onto the receiver, so the
// shadow's edge softens with the caster's height above the receiver. Only the receiver gets a
// shadow (docs/techniques.md).
#pragma once

#include <memory>
#include <string>

#include "raster_compare/gl/technique.h"

namespace so {

struct PlanarSettings {
    std::string technique;  // for errors about the receiver
    int receiver = -1;      // mesh index, -1: the largest planar mesh
    double lift = 1e-4;     // the receiver's plane raised towards the light (scene diagonals)
    bool stencil = true;    // each projection darkens a receiver pixel once
    double alpha = 1.0;     // the shadow's opacity
    int planes = 1;         // projections averaged
    double spacing = 0.0;   // between the shifted planes (scene diagonals)
};

std::unique_ptr<LightTechnique> setUpPlanarShadow(const PlanarSettings& settings,
                                                  const LightSetup& setup);

}  // namespace so
