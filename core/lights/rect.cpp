// `rect`: a one-sided parallelogram light at `center` with full edge vectors `u` and `v`, emitting
// on the side of cross(u, v) (docs/scene-format.md).
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "core/lights/light_kind.h"

namespace so {

namespace {

class RectLightKind final : public LightKind {
  public:
    LightType type() const override { return LightType::Rect; }
    const char* name() const override { return "rect"; }
    bool isArea() const override { return true; }
    bool oneSided() const override { return true; }
    std::vector<std::string> keys() const override { return {"center", "u", "v"}; }
    void parse(const json& j, const JsonReader& r, const std::string& f,
               Light& light) const override {
        light.wsPosition = r.vec3(need(j, r, f, "center"), f + ".center");
        light.wsU = r.vec3(need(j, r, f, "u"), f + ".u");
        light.wsV = r.vec3(need(j, r, f, "v"), f + ".v");
        const double lu = glm::length(light.wsU), lv = glm::length(light.wsV);
        if (!(lu > 0.0)) r.fail(f + ".u", "zero length (zero area)");
        if (!(lv > 0.0)) r.fail(f + ".v", "zero length (zero area)");
        const double area = glm::length(glm::cross(light.wsU, light.wsV));
        if (!(area > 1e-9 * lu * lv)) r.fail(f + ".v", "parallel to u (zero area)");
    }
    void write(const Light& l, json& j) const override {
        j["center"] = jsonVec3(l.wsPosition);
        j["u"] = jsonVec3(l.wsU);
        j["v"] = jsonVec3(l.wsV);
    }
    glm::dvec3 wsEmitNormal(const Light& l) const override {
        return glm::normalize(glm::cross(l.wsU, l.wsV));
    }
    GltfStandIn gltfStandIn(const Light& l, const Bounds3d& wsBounds) const override {
        return spotStandInAlongNormal(l, wsBounds);
    }
    void gltfExtras(const Light& l, json& j) const override {
        j["center"] = jsonVec3(l.wsPosition);
        j["edge_u"] = jsonVec3(l.wsU);
        j["edge_v"] = jsonVec3(l.wsV);
        j["normal"] = jsonVec3(wsEmitNormal(l));
    }
    double equalAreaDiameter(const Light& l) const override {
        return 2.0 * std::sqrt(glm::length(glm::cross(l.wsU, l.wsV)) / glm::pi<double>());
    }
};

}  // namespace

SO_REGISTER_LIGHT_KIND(RectLightKind);

}  // namespace so
