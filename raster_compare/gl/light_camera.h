// The shadow-map camera of each light (docs/techniques.md, "Light cameras"), in the local frame:
//   directional: orthographic in a light frame, fitted to the scene's bounds;
//   spot: perspective covering the outer cone (at most 170 degrees);
//   point, and area lights (from their centre): a cube map of six 90-degree faces.
// Depth runs 0 (near) to 1 (far) (glClipControl GL_ZERO_TO_ONE); near and far enclose the bounds.
#pragma once

#include <array>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"

namespace so {

struct LightCamera {
    enum class Kind { Ortho, Perspective, Cube };
    Kind kind = Kind::Ortho;
    int faces = 1;  // 6 for a cube
    std::array<glm::dmat4, 6> viewFromLocal{};
    glm::dmat4 clipFromView{1.0};
    double near = 0.0, far = 1.0;
    // Ortho: the world-space... local-space size of one texel; perspective and cube: per unit of
    // depth along the view axis (2 tan(fov / 2) / resolution).
    double texelScale = 0.0;
    double fovYDeg = 0.0;
    glm::dvec3 lsPosition{0.0}, lsDirection{0.0, -1.0, 0.0};
    double cosOuter = -1.0;  // spot
    glm::dmat4 clipFromLocal(int face) const { return clipFromView * viewFromLocal[size_t(face)]; }
};

// `lsReceivers` (optional, directional lights only): fit the map's x and y to these bounds (the
// receivers the camera sees) instead of the whole scene's; depth still spans the whole scene, so
// every occluder between the light and those receivers is in the map. Exact: along parallel rays
// only occluders inside the receivers' footprint can shadow them.
LightCamera fitLightCamera(const Light& light, const LocalFrame& frame, const Bounds3d& lsBounds,
                           int resolution, const Bounds3d* lsReceivers = nullptr);

// The width of an area light as the soft-shadow approximations take it (pcss, plateaus): the side
// of a square of its area (rect: sqrt(|u x v|); disk and sphere: r sqrt(pi)), world units; 0 for
// point, spot and directional lights.
double lightWidth(const Light& light);

}  // namespace so
