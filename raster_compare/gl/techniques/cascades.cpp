// cascades: cascaded shadow maps for directional lights, with slope-bias's lookup in each. The
// cascades themselves belong to the whole shadow-map family (shadow_map.h: the parameters
// cascades, split_lambda, snap, blend), so any technique's lookup runs in them: `pcf:cascades=4`,
// `vsm:cascades=2`; this entry is slope-bias with four cascades by default, the setting engines
// ship. Its shader is slope-bias's.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Cascades final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        ParamTable table = shadowMapParams(SlopeBias::params());
        for (ParamSpec& p : table)
            if (p.name == "cascades") p.defaultValue = 4;
        return table;
    }
    explicit Cascades(const ParamValues& v) : ShadowMapTechnique(v), bias_(v) {}
    const char* glsl() const override { return shaders::slope_bias_glsl; }
    std::string shaderDefines() const override { return bias_.defines(); }

  private:
    SlopeBias bias_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Cascades, "cascades",
                      "slope-bias in cascaded maps over the view's depth range (practical split, "
                      "optional sphere fit with texel snapping, blend band); any shadow-map "
                      "technique takes cascades=N too");

}  // namespace so
