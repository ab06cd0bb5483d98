// plane-shift: soft planar shadows by shifting the projection plane (Gooch, Gooch, Shirley and
// Cohen, "Interactive Technical Illustration", I3D 1999). The casters are projected from the one
// light onto `planes` planes, the receiver's and others shifted towards the light by `spacing`
// (scene diagonals) each, every projection flattened back onto the receiver, and the shadows
// averaged: a caster's shadow on a higher plane is smaller, so the edge softens more the higher
// the caster stands above the receiver, as a penumbra does. Same receiver rules and limits as
// `planar` (only the receiver gets a shadow); the stencil is always on, so each projection darkens
// a pixel once. Its penumbra follows the height, not the light's size: what the metrics measure.
#include "raster_compare/gl/volumes/planar_shadow.h"

namespace so {
namespace {

class PlaneShift final : public Technique {
  public:
    static constexpr const char* kFamily = "planar projection";
    static Provenance provenance() {
        return {
            "Gooch, Gooch, Shirley and Cohen, \"Interactive Technical Illustration\", I3D 1999, "
            "section 4.3 (soft shadows from projections onto planes shifted towards the light)",
            Fidelity::Faithful};
    }
    static ParamTable params() {
        return {receiverParam(),
                {"planes", 8, 1, 64, true, "projection planes averaged", {}, true},
                {"spacing", 0.005, 0.0, 0.5, false,
                 "between the planes, towards the light, in units of the scene's diagonal"},
                {"lift", 1e-4, 0.0, 0.1, false,
                 "the receiver's plane raised towards the light, in scene diagonals"},
                // `alpha` before issue 62, a name now left to alpha masks.
                renamedFrom(
                    {"opacity", 1.0, 0.0, 1.0, false, "shadow opacity under all planes' shadows"},
                    {"alpha", {}, "", 8})};
    }
    explicit PlaneShift(const ParamValues& v) : Technique(v) {
        settings_.technique = "plane-shift";
        settings_.receiver = v.integer("receiver");
        settings_.planes = v.integer("planes");
        settings_.spacing = v.real("spacing");
        settings_.lift = v.real("lift");
        settings_.opacity = v.real("opacity");
    }
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override {
        return setUpPlanarShadow(settings_, setup);
    }

  private:
    PlanarSettings settings_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(PlaneShift, "plane-shift",
                      "soft planar shadows: projections onto planes shifted towards the light, "
                      "averaged");

}  // namespace so
