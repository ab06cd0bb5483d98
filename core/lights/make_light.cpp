#include "core/lights/make_light.h"

#include <utility>

namespace so {

namespace {

Light named(std::string name, LightType type) {
    Light l;
    l.name = std::move(name);
    l.type = type;
    return l;
}

}  // namespace

Light pointLight(std::string name, const glm::dvec3& wsPosition) {
    Light l = named(std::move(name), LightType::Point);
    l.wsPosition = wsPosition;
    return l;
}

Light directionalLight(std::string name, const glm::dvec3& wsDirection) {
    Light l = named(std::move(name), LightType::Directional);
    l.wsDirection = wsDirection;
    return l;
}

Light spotLight(std::string name, const glm::dvec3& wsPosition, const glm::dvec3& wsDirection,
                double outerConeDeg, double innerConeDeg) {
    Light l = named(std::move(name), LightType::Spot);
    l.wsPosition = wsPosition;
    l.wsDirection = wsDirection;
    l.outerConeDeg = outerConeDeg;
    l.innerConeDeg = innerConeDeg;
    return l;
}

Light rectLight(std::string name, const glm::dvec3& wsCenter, const glm::dvec3& wsU,
                const glm::dvec3& wsV) {
    Light l = named(std::move(name), LightType::Rect);
    l.wsPosition = wsCenter;
    l.wsU = wsU;
    l.wsV = wsV;
    return l;
}

Light diskLight(std::string name, const glm::dvec3& wsCenter, const glm::dvec3& wsNormal,
                double radius) {
    Light l = named(std::move(name), LightType::Disk);
    l.wsPosition = wsCenter;
    l.wsNormal = wsNormal;
    l.radius = radius;
    return l;
}

Light sphereLight(std::string name, const glm::dvec3& wsCenter, double radius) {
    Light l = named(std::move(name), LightType::Sphere);
    l.wsPosition = wsCenter;
    l.radius = radius;
    return l;
}

Light pointLightAt(const Light& light, const glm::dvec3& wsPosition) {
    Light l = light;
    l.type = LightType::Point;
    l.wsPosition = wsPosition;
    return l;
}

}  // namespace so
