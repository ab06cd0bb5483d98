// The raster path's sphere light: points over the whole sphere (its silhouette's width).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

class SphereRasterLightKind final : public RasterAreaLightKind {
  public:
    LightType type() const override { return LightType::Sphere; }
    const char* emitterDefine() const override { return "#define EMITTER_SPHERE\n"; }
    double width(const Light& l) const override { return l.radius * std::sqrt(std::numbers::pi); }
    glm::dvec3 samplePoint(const Light& l, double u, double v) const override {
        const double phi = 2.0 * std::numbers::pi * v;
        const double z = 1.0 - 2.0 * u, s = std::sqrt(std::max(0.0, 1.0 - z * z));
        return l.wsPosition + l.radius * glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(SphereRasterLightKind);

}  // namespace so
