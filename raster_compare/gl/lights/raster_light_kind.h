// Area light types as plug-ins, the raster path's layer (core/lights/light_kind.h is the scene
// format's, oracle/lights/area_light_kind.h the oracle's): what a technique needs to know of an
// area light's shape. Every area light's shadow camera is the cube from its centre
// (light_camera.h) and its facing the one-sided or sphere emitter's (light_facing.h); what differs
// by type is here, one file each (rect.cpp, disk.cpp, sphere.cpp, polygon.cpp), one line each in
// raster_light_kind.cpp's table.
#pragma once

#include <glm/vec3.hpp>

#include "core/scene.h"

namespace so {

class RasterAreaLightKind {
  public:
    virtual ~RasterAreaLightKind() = default;
    virtual LightType type() const = 0;
    // The side of the square with the light's area seen face-on (sphere: of its silhouette disk):
    // the one size PCSS-like techniques take (light_camera.h, lightWidth).
    virtual double width(const Light& light) const = 0;
    // The point for (u, v) in [0, 1)^2, uniform by area over the light (sphere: the whole sphere),
    // world space: the soft techniques' light samples (light_samples.h).
    virtual glm::dvec3 samplePoint(const Light& light, double u, double v) const = 0;
};

// The registered kind of an area light type; null for punctual lights.
const RasterAreaLightKind* rasterAreaLightKind(LightType type);

const RasterAreaLightKind& rectRasterLightKind();
const RasterAreaLightKind& diskRasterLightKind();
const RasterAreaLightKind& sphereRasterLightKind();
const RasterAreaLightKind& polygonRasterLightKind();

}  // namespace so
