// `sphere`: a uniformly emitting sphere light at `center` with `radius` (docs/scene-format.md).
#include "core/lights/light_kind.h"

namespace so {

namespace {

class SphereLightKind final : public LightKind {
  public:
    LightType type() const override { return LightType::Sphere; }
    const char* name() const override { return "sphere"; }
    bool isArea() const override { return true; }
    std::vector<std::string> keys() const override { return {"center", "radius"}; }
    void parse(const json& j, const JsonReader& r, const std::string& f,
               Light& light) const override {
        light.wsPosition = r.vec3(need(j, r, f, "center"), f + ".center");
        light.radius = r.number(need(j, r, f, "radius"), f + ".radius");
        if (!(light.radius > 0.0)) r.outOfRange(f + ".radius", "> 0", light.radius);
    }
    void write(const Light& l, json& j) const override {
        j["center"] = jsonVec3(l.wsPosition);
        j["radius"] = l.radius;
    }
    // A point light at its centre: glTF has no sphere light.
    GltfStandIn gltfStandIn(const Light& l, const Bounds3d&) const override {
        GltfStandIn s;
        s.type = "point";
        s.wsAt = l.wsPosition;
        return s;
    }
    void gltfExtras(const Light& l, json& j) const override { write(l, j); }
    double equalAreaDiameter(const Light& l) const override { return 2.0 * l.radius; }
};

}  // namespace

SO_REGISTER_LIGHT_KIND(SphereLightKind);

}  // namespace so
