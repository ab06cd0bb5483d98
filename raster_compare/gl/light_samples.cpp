#include "raster_compare/gl/light_samples.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/sobol.h"

namespace so {

std::vector<glm::dvec3> lightSamplePoints(const Light& light, int n) {
    if (!isAreaLight(light.type)) return {light.wsPosition};
    std::vector<glm::dvec3> points;
    for (int i = 0; i < n; ++i) {
        float u = 0.0f, v = 0.0f;
        sobol2D(uint32_t(i), 0x5eedu, u, v);
        const double phi = 2.0 * std::numbers::pi * double(v);
        if (light.type == LightType::Rect) {
            points.push_back(light.wsPosition + (double(u) - 0.5) * light.wsU +
                             (double(v) - 0.5) * light.wsV);
        } else if (light.type == LightType::Disk) {
            const glm::dvec3 axis = glm::normalize(light.wsNormal);
            const glm::dvec3 a = glm::normalize(glm::cross(
                axis, std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
            const glm::dvec3 b = glm::cross(axis, a);
            const double r = light.radius * std::sqrt(double(u));
            points.push_back(light.wsPosition + r * (std::cos(phi) * a + std::sin(phi) * b));
        } else {
            const double z = 1.0 - 2.0 * double(u), s = std::sqrt(std::max(0.0, 1.0 - z * z));
            points.push_back(light.wsPosition +
                             light.radius * glm::dvec3(s * std::cos(phi), s * std::sin(phi), z));
        }
    }
    return points;
}

}  // namespace so
