// The raster path's disk light: radius r about its centre, in the plane across its normal.
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

// The disk's unit axes in its plane: a across the normal and the first world axis not nearly
// along it, b = normal x a.
void diskAxes(const Light& l, glm::dvec3& a, glm::dvec3& b) {
    const glm::dvec3 axis = glm::normalize(l.wsNormal);
    a = glm::normalize(
        glm::cross(axis, std::fabs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    b = glm::cross(axis, a);
}

class DiskRasterLightKind final : public RasterAreaLightKind {
  public:
    LightType type() const override { return LightType::Disk; }
    RasterLightShape shape(const Light& l) const override {
        glm::dvec3 a, b;
        diskAxes(l, a, b);
        return {RasterLightShape::Kind::Disk, l.wsPosition, l.radius * a, l.radius * b, 0.0};
    }
    double width(const Light& l) const override { return l.radius * std::sqrt(std::numbers::pi); }
    glm::dvec3 samplePoint(const Light& l, double u, double v) const override {
        const double phi = 2.0 * std::numbers::pi * v;
        glm::dvec3 a, b;
        diskAxes(l, a, b);
        const double r = l.radius * std::sqrt(u);
        return l.wsPosition + r * (std::cos(phi) * a + std::sin(phi) * b);
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(DiskRasterLightKind);

}  // namespace so
