#include "core/lights/light_kind.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "core/error.h"

namespace so {

namespace {

// The one table of light types, in LightType's order: registering a type is one line here.
const std::array<const LightKind*, 7>& table() {
    static const std::array<const LightKind*, 7> kinds = {
        &pointLightKind(), &directionalLightKind(), &spotLightKind(),   &rectLightKind(),
        &diskLightKind(),  &sphereLightKind(),      &polygonLightKind()};
    return kinds;
}

}  // namespace

const json& LightKind::need(const json& j, const JsonReader& r, const std::string& field,
                            const char* key) const {
    if (!j.contains(key))
        r.fail(field + "." + key, std::string("missing (required for a ") + name() + " light)");
    return j[key];
}

double innerConeBelowOuter(double innerRad, double outerRad) {
    return std::min(innerRad, std::nextafter(outerRad, 0.0));
}

GltfStandIn spotStandInAlongNormal(const Light& light, const Bounds3d& wsBounds) {
    const double minRad = glm::pi<double>() / 180.0, maxRad = 85.0 * minRad;
    const glm::dvec3 n = light.wsEmitNormal();
    double widest = minRad;
    bool inFront = false;
    for (int k = 0; k < 8 && !wsBounds.empty(); ++k) {
        const glm::dvec3 corner((k & 1) ? wsBounds.hi.x : wsBounds.lo.x,
                                (k & 2) ? wsBounds.hi.y : wsBounds.lo.y,
                                (k & 4) ? wsBounds.hi.z : wsBounds.lo.z);
        const glm::dvec3 d = corner - light.wsPosition;
        const double len = glm::length(d);
        if (!(len > 0.0) || glm::dot(d, n) <= 0.0) continue;
        inFront = true;
        widest = std::max(widest, std::acos(std::min(1.0, glm::dot(d, n) / len)));
    }
    GltfStandIn s;
    s.type = "spot";
    s.wsAt = light.wsPosition;
    s.wsAlong = n;
    s.outerConeRad = inFront ? std::min(widest, maxRad) : maxRad;
    s.innerConeRad = innerConeBelowOuter(s.outerConeRad, s.outerConeRad);
    return s;
}

const LightKind& lightKind(LightType t) {
    const size_t i = size_t(t);
    SO_CHECK(i < table().size() && table()[i]->type() == t);
    return *table()[i];
}

const LightKind* findLightKind(const std::string& name) {
    for (const LightKind* k : table())
        if (name == k->name()) return k;
    return nullptr;
}

std::string lightKindNames() {
    std::string list;
    for (const LightKind* k : table()) list += (list.empty() ? "" : ", ") + std::string(k->name());
    return list;
}

const char* lightTypeName(LightType t) {
    return lightKind(t).name();
}

bool isAreaLight(LightType t) {
    return lightKind(t).isArea();
}

glm::dvec3 Light::wsEmitNormal() const {
    return lightKind(type).wsEmitNormal(*this);
}

}  // namespace so
