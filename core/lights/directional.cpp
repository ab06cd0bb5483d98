// `directional`: parallel light travelling along the unit `direction` (docs/scene-format.md).
#include "core/lights/light_kind.h"

namespace so {

namespace {

class DirectionalLightKind final : public LightKind {
  public:
    LightType type() const override { return LightType::Directional; }
    const char* name() const override { return "directional"; }
    bool isDirectional() const override { return true; }
    bool pathMovesPosition() const override { return false; }
    bool pathTurnsDirection() const override { return true; }
    std::vector<std::string> keys() const override { return {"direction"}; }
    void parse(const json& j, const JsonReader& r, const std::string& f,
               Light& light) const override {
        light.wsDirection = r.unitVec3(need(j, r, f, "direction"), f + ".direction");
    }
    void write(const Light& l, json& j) const override { j["direction"] = jsonVec3(l.wsDirection); }
    GltfStandIn gltfStandIn(const Light& l, const Bounds3d& wsBounds) const override {
        GltfStandIn s;
        s.type = "directional";
        s.wsAlong = l.wsDirection;
        // No position in glTF's sense; engines whose directional shadow camera needs one get a
        // point one bounds diagonal upstream of the bounds' centre.
        s.wsAt = wsBounds.empty() ? glm::dvec3(0.0)
                                  : wsBounds.center() - l.wsDirection * wsBounds.extent();
        return s;
    }
    void gltfExtras(const Light& l, json& j) const override {
        j["direction"] = jsonVec3(l.wsDirection);
    }
};

}  // namespace

SO_REGISTER_LIGHT_KIND(DirectionalLightKind);

}  // namespace so
