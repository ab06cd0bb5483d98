#include "oracle/lights/area_light_kind.h"

#include "core/error.h"
#include "core/lights/light_kind.h"

namespace so {

namespace {

// The registered kinds by LightType; null for the punctual types. A type registered twice, or a
// kind for a type the scene format does not call an area light, is an InternalError at the first
// call.
std::vector<const AreaLightKind*> buildTable() {
    AreaLightKindList registered;
    registerBuiltInAreaLightKinds(registered);
    std::vector<const AreaLightKind*> byType(allLightKinds().size(), nullptr);
    for (const AreaLightKind* k : registered) {
        const size_t i = size_t(k->type());
        if (i >= byType.size() || byType[i] || !isAreaLight(k->type()))
            throw InternalError(std::string("area light kinds: ") + lightTypeName(k->type()) +
                                " is registered twice or is not an area light");
        byType[i] = k;
    }
    return byType;
}

[[noreturn]] void notOneSided(const Light& light) {
    throw InternalError(std::string("a ") + lightTypeName(light.type) +
                        " light has no emitting side");
}

}  // namespace

const AreaLightKind& areaLightKind(LightType type) {
    static const std::vector<const AreaLightKind*> table = buildTable();
    const size_t i = size_t(type);
    if (i < table.size() && table[i]) return *table[i];
    throw InternalError(std::string("no area light kind for a ") + lightTypeName(type) + " light");
}

int AreaLightKind::sideOfPlane(const Light& light, const glm::dvec3&) const {
    notOneSided(light);
}

bool AreaLightKind::abovePlane(const PixelTriangle&, const Light& light) const {
    notOneSided(light);
}

bool AreaLightKind::boundedDisk(const Light& light, const LocalFrame&, const glm::dvec3&,
                                DiskLightShape&) const {
    throw InternalError(std::string("the exact pass does not bound a ") +
                        lightTypeName(light.type) + " light over a disk");
}

}  // namespace so
