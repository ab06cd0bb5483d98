// cascades: cascaded shadow maps for directional lights, with basic's lookup in each at its bias
// (`bias`, by default the slope bias: slope-bias's lookup). The
// cascades themselves belong to the whole shadow-map family (shadow_map.h: the parameters
// cascades, split_lambda, snap, blend), so any technique's lookup runs in them: `pcf:cascades=4`,
// `vsm:cascades=2`; this entry is slope-bias with four cascades by default, the setting engines
// ship. Its shader is basic's.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Cascades final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "Zhang, Sun, Xu and Lun, \"Parallel-Split Shadow Maps for Large-scale Virtual "
            "Environments\", VRCIA 2006, section 3 (the practical split scheme, split_lambda)",
            Fidelity::Variant,
            {"options engines add, not in the paper: a bounding-sphere fit with texel snapping and "
             "a blend band between cascades",
             "the lookup in each cascade is basic's with the depth bias axis (slope by default)"}};
    }
    static ParamTable params() {
        ParamTable table = shadowMapParams(withBiasAxis({}, "slope"));
        for (ParamSpec& p : table)
            if (p.name == "cascades") p.defaultValue = 4;
        return table;
    }
    explicit Cascades(const ParamValues& v) : ShadowMapTechnique(v) {}
    const char* glsl() const override { return shaders::basic_glsl; }
};

}  // namespace

SO_REGISTER_TECHNIQUE(Cascades, "cascades",
                      "slope-bias in cascaded maps over the view's depth range (practical split, "
                      "optional sphere fit with texel snapping, blend band); any shadow-map "
                      "technique takes cascades=N too");

}  // namespace so
