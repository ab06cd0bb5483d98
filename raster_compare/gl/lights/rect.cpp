// The raster path's rect light: corners centre -+ u/2 -+ v/2.
#include <cmath>

#include <glm/geometric.hpp>

#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

class RectRasterLightKind final : public RasterAreaLightKind {
  public:
    LightType type() const override { return LightType::Rect; }
    RasterLightShape shape(const Light& l) const override {
        return {RasterLightShape::Kind::Rect, l.wsPosition, l.wsU, l.wsV, 0.0};
    }
    double width(const Light& l) const override {
        return std::sqrt(glm::length(glm::cross(l.wsU, l.wsV)));
    }
    glm::dvec3 samplePoint(const Light& l, double u, double v) const override {
        return l.wsPosition + (u - 0.5) * l.wsU + (v - 0.5) * l.wsV;
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(RectRasterLightKind);

}  // namespace so
