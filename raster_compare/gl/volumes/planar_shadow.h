// The planar-projection family: casters flattened onto a planar receiver from the light (Blinn
// 1988) and drawn over it. `planar` projects once; `plane-shift` (Gooch et al. 1999) averages the
// projections onto planes shifted towards the light, each flattened back onto the receiver, so the
// shadow's edge softens with the caster's height above the receiver. Only the receiver gets a
// shadow (docs/techniques.md).
#pragma once

#include <memory>
#include <string>

#include <epoxy/gl.h>

#include "raster_compare/gl/technique.h"

namespace so {

struct PlanarSettings {
    std::string technique;  // for errors about the receiver
    int receiver = -1;      // mesh index, -1: the largest planar mesh
    double lift = 1e-4;     // the receiver's plane raised towards the light (scene diagonals)
    bool stencil = true;    // each projection darkens a receiver pixel once
    double opacity = 1.0;   // the shadow's opacity
    int planes = 1;         // projections averaged
    double spacing = 0.0;   // between the shifted planes (scene diagonals)
};

std::unique_ptr<LightTechnique> setUpPlanarShadow(const PlanarSettings& settings,
                                                  const LightSetup& setup);

// The family's parameter naming the receiver, as every planar technique's table has it.
ParamSpec receiverParam();

// Stencil 1 on the receiver's visible pixels (drawn with `markProgram`, depth EQUAL to the camera
// pass's, colours masked), then the stencil test passing only there, a passing fragment doing
// `onPass` to the stencil (GL_ZERO: each pixel darkened once; GL_KEEP). The caller enables the
// stencil test.
void markReceiverStencil(GLuint markProgram, const GpuScene& scene, int receiverMesh,
                         GLenum onPass);

}  // namespace so
