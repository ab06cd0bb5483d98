// slope-bias: a bias that grows with the receiver's slope to the light, computed in the shader:
// eps = clamp(alpha * tan(acos(n.l)), min, max) texels. Within one
// texel a receiver tilted by theta spans tan(theta) texels of depth, which is what causes acne.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class SlopeBiasTechnique final : public ShadowMapTechnique {
  public:
    static ParamTable params() { return shadowMapParams(SlopeBias::params()); }
    explicit SlopeBiasTechnique(const ParamValues& v) : ShadowMapTechnique(v), bias_(v) {}
    const char* glsl() const override { return shaders::slope_bias_glsl; }
    std::string shaderDefines() const override { return bias_.defines(); }

  private:
    SlopeBias bias_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(SlopeBiasTechnique, "slope-bias",
                      "slope-scaled bias clamp(alpha tan(acos(n.l)), min, max)");

}  // namespace so
