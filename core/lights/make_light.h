// Typed constructors of lights, for code that makes a light rather than reading one from a scene
// file (the glTF loader's KHR_lights_punctual, the default sun, tests and benches): the fields a
// kind reads, set by name, so that no caller names a LightType. They check nothing; a scene file's
// lights are checked by their kinds' parse (core/lights/*.cpp).
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "core/scene.h"

namespace so {

Light pointLight(std::string name, const glm::dvec3& wsPosition);
// wsDirection: the way the light travels (unit, as a scene file's is).
Light directionalLight(std::string name, const glm::dvec3& wsDirection);
// Half-angles in degrees: outer in (0, 90], inner in [0, outer].
Light spotLight(std::string name, const glm::dvec3& wsPosition, const glm::dvec3& wsDirection,
                double outerConeDeg, double innerConeDeg = 0.0);
// Full edge vectors; emits on the side of cross(wsU, wsV).
Light rectLight(std::string name, const glm::dvec3& wsCenter, const glm::dvec3& wsU,
                const glm::dvec3& wsV);
// wsNormal: unit, the side it emits on.
Light diskLight(std::string name, const glm::dvec3& wsCenter, const glm::dvec3& wsNormal,
                double radius);
Light sphereLight(std::string name, const glm::dvec3& wsCenter, double radius);
// `light` as a point light at wsPosition, its other fields kept: how the soft raster techniques
// and the lightmap bake treat each sample point of an area light.
Light pointLightAt(const Light& light, const glm::dvec3& wsPosition);

}  // namespace so
