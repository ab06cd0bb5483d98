// The one place that builds a camera. Conventions (docs/conventions.md): right-handed world, the
// camera looks from eye to target, vfovDeg is the full vertical field of view, pixels are square,
// pixel (x, y) is sampled at its centre (x + 0.5, y + 0.5), and row 0 is the top of the image.
#pragma once

#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/scene.h"

namespace so {

struct Ray3d {
    glm::dvec3 origin;
    glm::dvec3 direction;  // unit length
};

class Camera {
  public:
    // Validates nothing: the scene loader has already rejected degenerate descriptions.
    explicit Camera(const CameraDesc& desc);

    int width() const { return width_; }
    int height() const { return height_; }
    const glm::dvec3& wsEye() const { return wsEye_; }

    // The primary ray through the centre of pixel (x, y), in world space.
    Ray3d generateRay(int x, int y) const;
    // The same ray at a continuous image position (pixel units, (0,0) = top-left corner).
    Ray3d generateRay(double imageX, double imageY) const;

    // The inverse of generateRay(double, double): the continuous image position (pixel units,
    // (0,0) = top-left corner) where the ray to wsPoint crosses the image plane; none for a point
    // not in front of the eye. The point may project outside [0, width) x [0, height).
    std::optional<glm::dvec2> project(const glm::dvec3& wsPoint) const;

    // For the raster path: OpenGL view and projection matrices that put the centre of pixel (x, y)
    // exactly where generateRay(x, y) points (window y flipped because GL's row 0 is the bottom).
    glm::dmat4 viewFromWorld() const;
    glm::dmat4 clipFromView(double zNear, double zFar) const;

    // Camera basis: right-handed, wsForward points at the target.
    glm::dvec3 wsRight() const { return wsRight_; }
    glm::dvec3 wsUp() const { return wsUp_; }
    glm::dvec3 wsForward() const { return wsForward_; }

  private:
    glm::dvec3 wsEye_, wsRight_, wsUp_, wsForward_;
    double tanHalfVfov_, aspect_;
    int width_, height_;
};

// Where a scene has no camera (a bare glTF without one): looks at the bounds' centre from the
// direction (1, 0.6, 1.2) with a 40 degree field of view, at the distance where the bounding
// sphere just fits vertically, 512x512. Documented in docs/scene-format.md.
CameraDesc defaultFraming(const Bounds3d& wsBounds);

}  // namespace so
