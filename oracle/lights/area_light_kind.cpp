#include "oracle/lights/area_light_kind.h"

#include "core/error.h"

namespace so {

const AreaLightKind& areaLightKind(LightType type) {
    // The oracle's table of area light types: registering one is one line here.
    switch (type) {
        case LightType::Rect:
            return rectAreaLightKind();
        case LightType::Disk:
            return diskAreaLightKind();
        case LightType::Sphere:
            return sphereAreaLightKind();
        case LightType::Polygon:
            return polygonAreaLightKind();
        default:
            break;
    }
    throw InternalError(std::string("no area light kind for a ") + lightTypeName(type) + " light");
}

}  // namespace so
