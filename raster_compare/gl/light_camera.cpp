#include "raster_compare/gl/light_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

namespace so {

namespace {

glm::dvec3 anyUp(const glm::dvec3& forward) {
    return std::fabs(forward.y) < 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
}

// Near and far planes around a point that enclose the bounds: far reaches the farthest corner;
// near is the distance to the box (a little less), but at least far / 1e4 for depth precision.
void enclose(const glm::dvec3& eye, const Bounds3d& b, double& near, double& far) {
    far = 0.0;
    for (int k = 0; k < 8; ++k) {
        glm::dvec3 c((k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y,
                     (k & 4) ? b.hi.z : b.lo.z);
        far = std::max(far, glm::length(c - eye));
    }
    far = far * 1.01 + 1e-6;
    const glm::dvec3 nearest = glm::clamp(eye, b.lo, b.hi);
    near = std::max(0.99 * glm::length(nearest - eye), far * 1e-4);
}

}  // namespace

LightCamera fitLightCamera(const Light& light, const LocalFrame& frame, const Bounds3d& b,
                           int resolution, const Bounds3d* lsReceivers) {
    LightCamera lc;
    lc.lsPosition = frame.lsFromWs(light.wsPosition);
    lc.lsDirection = glm::normalize(light.wsDirection);
    if (light.type == LightType::Directional) {
        lc.kind = LightCamera::Kind::Ortho;
        const glm::dvec3 centre = b.center();
        const double radius = 0.5 * b.extent() + 1e-6;
        const glm::dvec3 eye = centre - lc.lsDirection * (2.0 * radius);
        lc.viewFromLocal[0] = glm::lookAtRH(eye, centre, anyUp(lc.lsDirection));
        // Fit the box's corners in the light frame; square texels.
        auto fit = [&](const Bounds3d& box, glm::dvec3& lo, glm::dvec3& hi) {
            lo = glm::dvec3(1e300);
            hi = glm::dvec3(-1e300);
            for (int k = 0; k < 8; ++k) {
                glm::dvec3 c((k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y,
                             (k & 4) ? box.hi.z : box.lo.z);
                glm::dvec3 v = glm::dvec3(lc.viewFromLocal[0] * glm::dvec4(c, 1.0));
                lo = glm::min(lo, v);
                hi = glm::max(hi, v);
            }
        };
        glm::dvec3 lo, hi;
        fit(b, lo, hi);
        if (lsReceivers && !lsReceivers->empty()) {
            glm::dvec3 rlo, rhi;
            fit(*lsReceivers, rlo, rhi);
            lo.x = rlo.x, lo.y = rlo.y, hi.x = rhi.x, hi.y = rhi.y;
        }
        const double half = 0.5 * std::max(hi.x - lo.x, hi.y - lo.y) * 1.01;
        const double cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y);
        lc.near = std::max(0.0, -hi.z - 0.01 * radius);
        lc.far = -lo.z + 0.01 * radius;
        lc.clipFromView =
            glm::orthoRH_ZO(cx - half, cx + half, cy - half, cy + half, lc.near, lc.far);
        lc.texelScale = 2.0 * half / resolution;
        return lc;
    }
    enclose(lc.lsPosition, b, lc.near, lc.far);
    if (light.type == LightType::Spot) {
        lc.kind = LightCamera::Kind::Perspective;
        lc.fovYDeg = std::min(170.0, 2.0 * light.outerConeDeg * 1.02);
        lc.cosOuter = std::cos(light.outerConeDeg * std::numbers::pi / 180.0);
        lc.viewFromLocal[0] =
            glm::lookAtRH(lc.lsPosition, lc.lsPosition + lc.lsDirection, anyUp(lc.lsDirection));
        const double fov = lc.fovYDeg * std::numbers::pi / 180.0;
        lc.clipFromView = glm::perspectiveRH_ZO(fov, 1.0, lc.near, lc.far);
        lc.texelScale = 2.0 * std::tan(0.5 * fov) / resolution;
        return lc;
    }
    // Point lights, and area lights from their centre: the GL cube-map face order and orientation.
    lc.kind = LightCamera::Kind::Cube;
    lc.faces = 6;
    lc.fovYDeg = 90.0;
    const glm::dvec3 dirs[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    const glm::dvec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                               {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    for (int f = 0; f < 6; ++f)
        lc.viewFromLocal[size_t(f)] = glm::lookAtRH(lc.lsPosition, lc.lsPosition + dirs[f], ups[f]);
    lc.clipFromView = glm::perspectiveRH_ZO(std::numbers::pi / 2, 1.0, lc.near, lc.far);
    lc.texelScale = 2.0 / resolution;
    return lc;
}

double lightWidth(const Light& light) {
    switch (light.type) {
        case LightType::Rect:
            return std::sqrt(glm::length(glm::cross(light.wsU, light.wsV)));
        case LightType::Disk:
        case LightType::Sphere:
            return light.radius * std::sqrt(std::numbers::pi);
        default:
            return 0.0;
    }
}

}  // namespace so
