// The visibility frame of families without a map (shadow volumes, planar shadows): V = 1 where the
// light faces the surface, the surface is in front of a one-sided emitter and a spot's cone holds
// it, 0 elsewhere, as in the oracle; what the family then does (a stencil test, a projected shadow
// over it) makes the shadow.
#pragma once

#include "core/scene.h"
#include "raster_compare/gl/context/gl_object.h"

namespace so {

class CameraPass;
class GpuScene;

// scene.vert and shaders/light_facing.frag, with the light's and the camera's uniforms set.
GlProgram buildLightFacingProgram(const Light& light, const GpuScene& scene,
                                  const CameraPass& camera);

}  // namespace so
