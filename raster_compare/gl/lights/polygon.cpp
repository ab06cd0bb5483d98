// The raster path's polygon light: its fan of triangles from vertex 0, a triangle picked by its
// share of the area with u, the rest of u and v placing the point in it.
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

// Twice each fan triangle's area.
std::vector<double> fanAreas(const Light& l) {
    std::vector<double> a;
    const std::vector<glm::dvec3>& v = l.wsVertices;
    for (size_t k = 1; k + 1 < v.size(); ++k)
        a.push_back(glm::length(glm::cross(v[k] - v[0], v[k + 1] - v[0])));
    return a;
}

class PolygonRasterLightKind final : public RasterAreaLightKind {
  public:
    LightType type() const override { return LightType::Polygon; }
    RasterLightShape shape(const Light& l) const override {
        return {RasterLightShape::Kind::Polygon, l.wsPosition, {}, {}, 0.0};
    }
    double width(const Light& l) const override {
        double twice = 0.0;
        for (double a : fanAreas(l)) twice += a;
        return std::sqrt(0.5 * twice);
    }
    glm::dvec3 samplePoint(const Light& l, double u, double v) const override {
        const std::vector<double> areas = fanAreas(l);
        double total = 0.0;
        for (double a : areas) total += a;
        double target = u * total;
        size_t t = 0;
        while (t + 1 < areas.size() && target >= areas[t]) target -= areas[t++];
        const double r = std::sqrt(std::clamp(target / areas[t], 0.0, 1.0));
        const std::vector<glm::dvec3>& p = l.wsVertices;
        return (1.0 - r) * p[0] + r * (1.0 - v) * p[t + 1] + r * v * p[t + 2];
    }
};

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(PolygonRasterLightKind);

}  // namespace so
