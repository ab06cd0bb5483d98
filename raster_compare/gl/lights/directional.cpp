// The raster path's directional light: an orthographic camera along its direction.
#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

class DirectionalRasterLightKind final : public RasterLightKind {
  public:
    LightType type() const override { return LightType::Directional; }
    LightCamera::Kind cameraKind() const override { return LightCamera::Kind::Ortho; }
    RasterLightShape shape(const Light& l) const override {
        return {RasterLightShape::Kind::Direction, l.wsPosition, {}, {}, 0.0};
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(DirectionalRasterLightKind);

}  // namespace so
