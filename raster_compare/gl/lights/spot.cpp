// The raster path's spot light: a perspective camera over its cone.
#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

class SpotRasterLightKind final : public RasterLightKind {
  public:
    LightType type() const override { return LightType::Spot; }
    LightCamera::Kind cameraKind() const override { return LightCamera::Kind::Perspective; }
    RasterLightShape shape(const Light& l) const override {
        return {RasterLightShape::Kind::Point, l.wsPosition, {}, {}, 0.0};
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(SpotRasterLightKind);

}  // namespace so
