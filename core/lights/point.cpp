// `point`: a point light at `position`, shining every way (docs/scene-format.md).
#include "core/lights/light_kind.h"

namespace so {

namespace {

class PointLightKind final : public LightKind {
  public:
    LightType type() const override { return LightType::Point; }
    const char* name() const override { return "point"; }
    std::vector<std::string> keys() const override { return {"position"}; }
    void parse(const json& j, const JsonReader& r, const std::string& f,
               Light& light) const override {
        light.wsPosition = r.vec3(need(j, r, f, "position"), f + ".position");
    }
    void write(const Light& l, json& j) const override { j["position"] = jsonVec3(l.wsPosition); }
    GltfStandIn gltfStandIn(const Light& l, const Bounds3d&) const override {
        GltfStandIn s;
        s.type = "point";
        s.wsAt = l.wsPosition;
        return s;
    }
    void gltfExtras(const Light&, json&) const override {}
};

}  // namespace

SO_REGISTER_LIGHT_KIND(PointLightKind);

}  // namespace so
