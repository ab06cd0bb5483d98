// The raster path's sphere light: points over the whole sphere (its silhouette's width); a
// receiver's shadow rays sample the cap it sees.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

class SphereRasterLightKind final : public RasterAreaLightKind {
  public:
    LightType type() const override { return LightType::Sphere; }
    const char* emitterDefine() const override { return "#define EMITTER_SPHERE\n"; }
    RasterLightShape shape(const Light& l) const override {
        return {RasterLightShape::Kind::Sphere, l.wsPosition, {}, {}, l.radius};
    }
    double width(const Light& l) const override { return l.radius * std::sqrt(std::numbers::pi); }
    glm::dvec3 samplePoint(const Light& l, double u, double v) const override {
        const double phi = 2.0 * std::numbers::pi * v;
        const double z = 1.0 - 2.0 * u, s = std::sqrt(std::max(0.0, 1.0 - z * z));
        return l.wsPosition + l.radius * glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
    }
    LightPoint pointSeenFrom(const Light& l, const glm::dvec3& wsFrom, double u,
                             double v) const override;
};

// Uniform by area over the cap that wsFrom sees (the same ratio estimate as over the whole
// sphere, whose other samples have G = 0: at one ray a pixel most pixels would otherwise get
// none): the whole sphere's point for (u, v), its cos(theta) from the axis towards wsFrom mapped
// affinely onto [r / D, 1]. Inside the sphere (or for a radius 0) the whole sphere's point: the
// oracle's V is 0 there, and so is G. The normal is the sphere's outward one.
LightPoint SphereRasterLightKind::pointSeenFrom(const Light& l, const glm::dvec3& wsFrom, double u,
                                                double v) const {
    glm::dvec3 ws = samplePoint(l, u, v);
    const glm::dvec3 toP = wsFrom - l.wsPosition;
    const double D = glm::length(toP), r = l.radius;
    if (D > r && r > 0.0) {
        const glm::dvec3 axis = toP / D;
        const glm::dvec3 radial = (ws - l.wsPosition) / r;
        const double cosT = glm::dot(radial, axis);
        glm::dvec3 tangent = radial - cosT * axis;
        const double sinT = glm::length(tangent);
        tangent = sinT > 1e-12 ? tangent / sinT : glm::dvec3(0.0);
        const double k = r / D, cosCap = k + (1.0 - k) * std::abs(cosT);
        const double sinCap = std::sqrt(std::max(0.0, 1.0 - cosCap * cosCap));
        ws = l.wsPosition + r * (cosCap * axis + sinCap * tangent);
    }
    return {ws, glm::normalize(ws - l.wsPosition)};
}

}  // namespace

SO_REGISTER_RASTER_LIGHT_KIND(SphereRasterLightKind);

}  // namespace so
