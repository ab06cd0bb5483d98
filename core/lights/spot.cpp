// `spot`: a point light at `position` lighting the cone of half-angle `outer_cone_deg` about the
// unit `direction`; `inner_cone_deg` (default 0) is where its falloff starts, for the raster path
// only (docs/scene-format.md).
#include <glm/gtc/constants.hpp>

#include "core/lights/light_kind.h"

namespace so {

namespace {

class SpotLightKind final : public LightKind {
  public:
    LightType type() const override { return LightType::Spot; }
    const char* name() const override { return "spot"; }
    bool hasCone() const override { return true; }
    bool pathTurnsDirection() const override { return true; }
    std::vector<std::string> keys() const override {
        return {"position", "direction", "outer_cone_deg", "inner_cone_deg"};
    }
    void parse(const json& j, const JsonReader& r, const std::string& f,
               Light& light) const override {
        light.wsPosition = r.vec3(need(j, r, f, "position"), f + ".position");
        light.wsDirection = r.unitVec3(need(j, r, f, "direction"), f + ".direction");
        light.outerConeDeg = r.number(need(j, r, f, "outer_cone_deg"), f + ".outer_cone_deg");
        if (!(light.outerConeDeg > 0.0 && light.outerConeDeg <= 90.0))
            r.outOfRange(f + ".outer_cone_deg", "in (0, 90] degrees (a half-angle)",
                         light.outerConeDeg);
        light.innerConeDeg = 0.0;
        if (j.contains("inner_cone_deg")) {
            light.innerConeDeg = r.number(j["inner_cone_deg"], f + ".inner_cone_deg");
            if (!(light.innerConeDeg >= 0.0 && light.innerConeDeg <= light.outerConeDeg))
                r.outOfRange(f + ".inner_cone_deg", "in [0, outer_cone_deg]", light.innerConeDeg);
        }
    }
    void write(const Light& l, json& j) const override {
        j["position"] = jsonVec3(l.wsPosition);
        j["direction"] = jsonVec3(l.wsDirection);
        j["outer_cone_deg"] = l.outerConeDeg;
        j["inner_cone_deg"] = l.innerConeDeg;
    }
    GltfStandIn gltfStandIn(const Light& l, const Bounds3d&) const override {
        const double degToRad = glm::pi<double>() / 180.0;
        GltfStandIn s;
        s.type = "spot";
        s.wsAt = l.wsPosition;
        s.wsAlong = l.wsDirection;
        s.outerConeRad = l.outerConeDeg * degToRad;
        s.innerConeRad = innerConeBelowOuter(l.innerConeDeg * degToRad, s.outerConeRad);
        return s;
    }
    void gltfExtras(const Light& l, json& j) const override {
        j["outer_cone_deg"] = l.outerConeDeg;
        j["inner_cone_deg"] = l.innerConeDeg;
    }
};

}  // namespace

SO_REGISTER_LIGHT_KIND(SpotLightKind);

}  // namespace so
