#include "raster_compare/gl/lights/light_samples.h"

#include "core/sobol.h"
#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

std::vector<glm::dvec3> lightSamplePoints(const Light& light, int n) {
    const RasterAreaLightKind* kind = rasterAreaLightKind(light.type);
    if (!kind) return {light.wsPosition};
    std::vector<glm::dvec3> points;
    for (int i = 0; i < n; ++i) {
        float u = 0.0f, v = 0.0f;
        sobol2D(uint32_t(i), 0x5eedu, u, v);
        points.push_back(kind->samplePoint(light, double(u), double(v)));
    }
    return points;
}

}  // namespace so
