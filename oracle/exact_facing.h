// Exact facing decisions for one pixel (docs/oracle.md, "Exact facing"). The float tests of the
// shadow passes decide almost every pixel; where a float value lies within its own rounding error
// of a boundary (the light in the plane of the surface, the surface in the plane of a one-sided
// emitter), these decide instead, exactly, on the scene's world-space doubles. The answers hold
// for every point of the pixel's triangle, as each boundary is a plane through the light or
// through the triangle.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "core/scene.h"
#include "oracle/accel.h"
#include "oracle/surface_buffer.h"

namespace so {

// The triangle a pixel sees, as the scene gives it (world space, double), ordered so that
// (b - a) x (c - a) points to the side the pixel's normal faces (towards the camera).
struct PixelTriangle {
    glm::dvec3 a{0.0}, b{0.0}, c{0.0};
};
PixelTriangle pixelTriangle(const Accel& accel, const SurfaceBuffer& sb, size_t slot);

// +1 where the light is strictly on the normal's side of the triangle's plane, 0 in it, -1 below.
int facingPoint(const PixelTriangle& t, const glm::dvec3& wsLight);
// The same for a direction towards the light (a directional light's -wsDirection).
int facingDirection(const PixelTriangle& t, const glm::dvec3& wsToLight);

// A one-sided emitter (rect, disk, polygon): +1 where every point of the triangle is strictly on
// the side it emits to, -1 where every point is on its plane or behind it, 0 where the plane cuts
// the triangle (then the point itself decides, in float).
int emitterSide(const PixelTriangle& t, const Light& light);

// Whether some point of an area light (rect, disk, polygon) lies strictly on the normal's side of
// the triangle's plane (false: the whole light is below the horizon or in the plane).
bool areaLightAbovePlane(const PixelTriangle& t, const Light& light);

// Decisions are the same for every pixel of one triangle: a one-entry cache per thread and light,
// keyed by the triangle's Accel::originId, spares neighbouring pixels the exact arithmetic.
struct FacingCache {
    uint32_t triangle = 0xFFFFFFFFu;
    int8_t facing = 0, emitter = 0;
    bool above = false;
};

}  // namespace so
