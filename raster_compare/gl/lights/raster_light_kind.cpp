#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

const RasterAreaLightKind* rasterAreaLightKind(LightType type) {
    // The raster path's table of area light types: registering one is one line here.
    switch (type) {
        case LightType::Rect:
            return &rectRasterLightKind();
        case LightType::Disk:
            return &diskRasterLightKind();
        case LightType::Sphere:
            return &sphereRasterLightKind();
        case LightType::Polygon:
            return &polygonRasterLightKind();
        default:
            return nullptr;
    }
}

}  // namespace so
