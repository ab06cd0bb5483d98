// `disk`: a one-sided disk light at `center` with unit `normal` (the side it emits on) and
// `radius` (docs/scene-format.md).
#include "core/lights/light_kind.h"

namespace so {

namespace {

class DiskLightKind final : public LightKind {
  public:
    LightType type() const override { return LightType::Disk; }
    const char* name() const override { return "disk"; }
    bool isArea() const override { return true; }
    bool oneSided() const override { return true; }
    std::vector<std::string> keys() const override { return {"center", "normal", "radius"}; }
    void parse(const json& j, const JsonReader& r, const std::string& f,
               Light& light) const override {
        light.wsPosition = r.vec3(need(j, r, f, "center"), f + ".center");
        light.wsNormal = r.unitVec3(need(j, r, f, "normal"), f + ".normal");
        light.radius = r.number(need(j, r, f, "radius"), f + ".radius");
        if (!(light.radius > 0.0)) r.outOfRange(f + ".radius", "> 0", light.radius);
    }
    void write(const Light& l, json& j) const override {
        j["center"] = jsonVec3(l.wsPosition);
        j["normal"] = jsonVec3(l.wsNormal);
        j["radius"] = l.radius;
    }
    glm::dvec3 wsEmitNormal(const Light& l) const override { return l.wsNormal; }
    GltfStandIn gltfStandIn(const Light& l, const Bounds3d& wsBounds) const override {
        return spotStandInAlongNormal(l, wsBounds);
    }
    void gltfExtras(const Light& l, json& j) const override { write(l, j); }
    double equalAreaDiameter(const Light& l) const override { return 2.0 * l.radius; }
};

}  // namespace

SO_REGISTER_LIGHT_KIND(DiskLightKind);

}  // namespace so
