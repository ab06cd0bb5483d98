#include "core/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace so {

Camera::Camera(const CameraDesc& desc)
    : wsEye_(desc.wsEye), width_(desc.width), height_(desc.height) {
    wsForward_ = glm::normalize(desc.wsTarget - desc.wsEye);
    wsRight_ = glm::normalize(glm::cross(wsForward_, desc.wsUp));
    wsUp_ = glm::cross(wsRight_, wsForward_);
    tanHalfVfov_ = std::tan(0.5 * desc.vfovDeg * std::numbers::pi / 180.0);
    aspect_ = double(width_) / double(height_);
}

Ray3d Camera::generateRay(int x, int y) const {
    return generateRay(x + 0.5, y + 0.5);
}

Ray3d Camera::generateRay(double imageX, double imageY) const {
    // Normalised device coordinates in [-1, 1]; image row 0 is the top, so y flips.
    double ndcX = 2.0 * imageX / width_ - 1.0;
    double ndcY = 1.0 - 2.0 * imageY / height_;
    glm::dvec3 d =
        wsForward_ + (ndcX * tanHalfVfov_ * aspect_) * wsRight_ + (ndcY * tanHalfVfov_) * wsUp_;
    return {wsEye_, glm::normalize(d)};
}

std::optional<glm::dvec2> Camera::project(const glm::dvec3& wsPoint) const {
    const glm::dvec3 vsPoint = wsPoint - wsEye_;
    const double depth = glm::dot(vsPoint, wsForward_);
    if (!(depth > 0.0)) return std::nullopt;
    // generateRay's d = forward + ndcX tan aspect right + ndcY tan up, scaled to depth 1.
    const double ndcX = glm::dot(vsPoint, wsRight_) / (depth * tanHalfVfov_ * aspect_);
    const double ndcY = glm::dot(vsPoint, wsUp_) / (depth * tanHalfVfov_);
    return glm::dvec2(0.5 * (ndcX + 1.0) * width_, 0.5 * (1.0 - ndcY) * height_);
}

glm::dmat4 Camera::viewFromWorld() const {
    glm::dmat4 m(1.0);
    // Rows are the camera axes; the view looks down -Z as OpenGL expects.
    for (int i = 0; i < 3; ++i) {
        m[i][0] = wsRight_[i];
        m[i][1] = wsUp_[i];
        m[i][2] = -wsForward_[i];
    }
    m[3][0] = -glm::dot(wsRight_, wsEye_);
    m[3][1] = -glm::dot(wsUp_, wsEye_);
    m[3][2] = glm::dot(wsForward_, wsEye_);
    return m;
}

glm::dmat4 Camera::clipFromView(double zNear, double zFar) const {
    glm::dmat4 m(0.0);
    m[0][0] = 1.0 / (aspect_ * tanHalfVfov_);
    m[1][1] = 1.0 / tanHalfVfov_;
    m[2][2] = -(zFar + zNear) / (zFar - zNear);
    m[2][3] = -1.0;
    m[3][2] = -2.0 * zFar * zNear / (zFar - zNear);
    return m;
}

CameraDesc defaultFraming(const Bounds3d& wsBounds) {
    CameraDesc desc;
    desc.vfovDeg = 40.0;
    desc.width = desc.height = 512;
    glm::dvec3 center = wsBounds.empty() ? glm::dvec3(0.0) : wsBounds.center();
    double radius = std::max(0.5 * wsBounds.extent(), 1e-3);
    double distance = radius / std::sin(0.5 * desc.vfovDeg * std::numbers::pi / 180.0);
    desc.wsTarget = center;
    desc.wsEye = center + distance * glm::normalize(glm::dvec3(1.0, 0.6, 1.2));
    desc.wsUp = glm::dvec3(0.0, 1.0, 0.0);
    return desc;
}

}  // namespace so
