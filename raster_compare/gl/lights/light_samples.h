// Points on a light as the raster path samples it (accumulate, the lightmap's bake): `n` points
// of an Owen-scrambled Sobol sequence, as the oracle's samples are, uniform by area on rect and
// disk lights and uniform over a sphere light's surface; a light that is not an area light is its
// own single point.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "core/scene.h"

namespace so {

// World space.
std::vector<glm::dvec3> lightSamplePoints(const Light& light, int n);

}  // namespace so
