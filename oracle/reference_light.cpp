#include "oracle/reference_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace so {

ReferenceLight::ReferenceLight(const Light& light, const LocalFrame& frame)
    : type_(light.type), m_(light.wsEmitNormal()) {
    const double s = frame.lsLength(1.0);
    c_ = frame.lsFromWs(light.wsPosition);
    u_ = light.wsU * s;
    v_ = light.wsV * s;
    radius_ = light.radius * s;
    if (type_ == LightType::Disk) {  // an orthonormal basis of the disk's plane
        const glm::dvec3 helper = std::fabs(m_.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        e1_ = glm::normalize(glm::cross(helper, m_));
        e2_ = glm::cross(m_, e1_);
    }
    if (type_ == LightType::Polygon) {
        for (const glm::dvec3& w : light.wsVertices) vertices_.push_back(frame.lsFromWs(w));
        double total = 0.0;
        for (size_t k = 1; k + 1 < vertices_.size(); ++k) {
            const glm::dvec3 a = vertices_[k] - vertices_[0], b = vertices_[k + 1] - vertices_[0];
            fanCdf_.push_back(total += glm::length(glm::cross(a, b)));
        }
        for (double& f : fanCdf_) f /= total;
    }
}

void ReferenceLight::point(double u1, double u2, glm::dvec3& y, glm::dvec3& ny) const {
    if (type_ == LightType::Rect) {
        y = c_ + (u1 - 0.5) * u_ + (u2 - 0.5) * v_;
        ny = m_;
    } else if (type_ == LightType::Disk) {
        const double r = radius_ * std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
        y = c_ + r * (std::cos(phi) * e1_ + std::sin(phi) * e2_);
        ny = m_;
    } else if (type_ == LightType::Polygon) {
        size_t t = 0;
        while (t + 1 < fanCdf_.size() && u1 >= fanCdf_[t]) ++t;
        const double lo = t ? fanCdf_[t - 1] : 0.0;
        const double r = std::sqrt(std::min(1.0, (u1 - lo) / (fanCdf_[t] - lo)));
        y = (1.0 - r) * vertices_[0] + r * (1.0 - u2) * vertices_[t + 1] +
            r * u2 * vertices_[t + 2];
        ny = m_;
    } else {  // sphere: uniform by area over the whole sphere
        const double zc = 1.0 - 2.0 * u1, rr = std::sqrt(std::max(0.0, 1.0 - zc * zc));
        const double phi = 2.0 * std::numbers::pi * u2;
        ny = glm::dvec3(rr * std::cos(phi), rr * std::sin(phi), zc);
        y = c_ + radius_ * ny;
    }
}

}  // namespace so
