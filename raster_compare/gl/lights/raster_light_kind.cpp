#include "raster_compare/gl/lights/raster_light_kind.h"

#include "core/error.h"
#include "core/lights/light_kind.h"

namespace so {

namespace {

// The registered kinds by LightType: every type exactly one (an InternalError at the first call
// otherwise, naming the type).
std::vector<const RasterLightKind*> buildTable() {
    RasterLightKindList registered;
    registerBuiltInRasterLightKinds(registered);
    std::vector<const RasterLightKind*> byType(allLightKinds().size(), nullptr);
    for (const RasterLightKind* k : registered) {
        const size_t i = size_t(k->type());
        if (i >= byType.size() || byType[i] || (k->area() != nullptr) != isAreaLight(k->type()))
            throw InternalError(std::string("raster light kinds: ") + lightTypeName(k->type()) +
                                " is registered twice or disagrees with the scene format on "
                                "whether it is an area light");
        byType[i] = k;
    }
    for (size_t i = 0; i < byType.size(); ++i)
        if (!byType[i])
            throw InternalError(std::string("no raster light kind for a ") +
                                allLightKinds()[i]->name() + " light");
    return byType;
}

}  // namespace

LightPoint RasterLightKind::pointSeenFrom(const Light& light, const glm::dvec3&, double,
                                          double) const {
    return {light.wsPosition, glm::dvec3(0.0)};
}

LightPoint RasterAreaLightKind::pointSeenFrom(const Light& light, const glm::dvec3&, double u,
                                              double v) const {
    return {samplePoint(light, u, v), light.wsEmitNormal()};
}

const RasterLightKind& rasterLightKind(LightType type) {
    static const std::vector<const RasterLightKind*> table = buildTable();
    const size_t i = size_t(type);
    SO_CHECK(i < table.size());
    return *table[i];
}

}  // namespace so
