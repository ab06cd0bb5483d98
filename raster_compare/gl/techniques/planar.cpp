// planar: planar projected shadows (Blinn, "Me and My (Fake) Shadow", 1988). Every mesh but the
// receiver is flattened onto the receiver's plane from the light and drawn over it, darkening V to
// 1 - opacity. Only the receiver gets a shadow: shadows on other surfaces and self-shadowing are
// absent by design (false lit, which the metrics count). The course's three fixes are parameters:
// `lift` (the plane raised towards the light against z-fighting, in units of the scene's
// diagonal), `stencil` (the shadow kept to the receiver's pixels and each pixel darkened once:
// without it overlapping projected triangles darken twice, visible with opacity < 1, and the
// shadow runs off the receiver's edges) and `opacity` (the shadow's; `alpha` before issue 62, a
// name now left to alpha masks). Casters below the plane or
// beyond a point light are clipped (w <= 0), not projected into false shadows.
#include "raster_compare/gl/volumes/planar_shadow.h"

namespace so {
namespace {

class Planar final : public Technique {
  public:
    static constexpr const char* kFamily = "planar projection";
    static Provenance provenance() {
        return {
            "Blinn, \"Me and My (Fake) Shadow\", IEEE CG&A 1988: casters flattened onto the "
            "receiver's plane from the light",
            Fidelity::Faithful};
    }
    static ParamTable params() {
        return {receiverParam(),
                {"lift", 1e-4, 0.0, 0.1, false,
                 "the plane raised towards the light, in units of the scene's diagonal"},
                methodParam("stencil", 1, {"off", "on"},
                            "on: shadow only on the receiver's pixels, each darkened once; off: "
                            "no stencil"),
                renamedFrom({"opacity", 1.0, 0.0, 1.0, false,
                             "the shadow's opacity: V = 1 - opacity in shadow"},
                            {"alpha", {}, "", 8})};
    }
    explicit Planar(const ParamValues& v) : Technique(v) {
        settings_.technique = "planar";
        settings_.receiver = v.integer("receiver");
        settings_.lift = v.real("lift");
        settings_.stencil = v.integer("stencil") == 1;
        settings_.opacity = v.real("opacity");
    }
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override {
        return setUpPlanarShadow(settings_, setup);
    }

  private:
    PlanarSettings settings_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Planar, "planar",
                      "planar projected shadows: casters flattened onto the receiver's plane");

}  // namespace so
