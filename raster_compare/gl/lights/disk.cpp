// The raster path's disk light: radius r about its centre, in the plane across its normal.
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

class DiskRasterLightKind final : public RasterAreaLightKind {
  public:
    LightType type() const override { return LightType::Disk; }
    double width(const Light& l) const override { return l.radius * std::sqrt(std::numbers::pi); }
    glm::dvec3 samplePoint(const Light& l, double u, double v) const override {
        const double phi = 2.0 * std::numbers::pi * v;
        const glm::dvec3 axis = glm::normalize(l.wsNormal);
        const glm::dvec3 a = glm::normalize(
            glm::cross(axis, std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        const glm::dvec3 b = glm::cross(axis, a);
        const double r = l.radius * std::sqrt(u);
        return l.wsPosition + r * (std::cos(phi) * a + std::sin(phi) * b);
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(DiskRasterLightKind);

}  // namespace so
