// The raster path's point light: the cube from its position, one sample.
#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

class PointRasterLightKind final : public RasterLightKind {
  public:
    LightType type() const override { return LightType::Point; }
    RasterLightShape shape(const Light& l) const override {
        return {RasterLightShape::Kind::Point, l.wsPosition, {}, {}, 0.0};
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(PointRasterLightKind);

}  // namespace so
