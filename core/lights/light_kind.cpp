#include "core/lights/light_kind.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "core/error.h"

namespace so {

namespace {

// The registered kinds in LightType's order, so that a type's kind is at its index and the error
// messages list the types in the scene format's order. Every value from 0 up has exactly one kind.
LightKindList buildTable() {
    LightKindList kinds;
    registerBuiltInLightKinds(kinds);
    std::sort(kinds.begin(), kinds.end(),
              [](const LightKind* a, const LightKind* b) { return a->type() < b->type(); });
    for (size_t i = 0; i < kinds.size(); ++i)
        if (size_t(kinds[i]->type()) != i)
            throw InternalError(std::string("light kinds: ") + kinds[i]->name() +
                                " is registered twice or a type before it has no kind");
    return kinds;
}

const LightKindList& table() {
    static const LightKindList kinds = buildTable();
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

const std::vector<const LightKind*>& allLightKinds() {
    return table();
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
