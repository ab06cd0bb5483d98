// adaptive-bias: adaptive depth bias (Dou, Yan, Kerzner, Dai, Wyman, "Adaptive Depth Bias for
// Shadow Maps", I3D 2014; JCGT 2015). The ray from the light through the centre of the texel the
// lookup reads meets the receiver's tangent plane (from its geometric normal) at the depth the
// receiver would have stored there; that depth, less a margin for the depth buffer's precision at
// that depth (the paper's adaptive epsilon; here `epsilon` steps of the buffer's last bit,
// DepthPrecision), is compared with the map. The bias can be either sign: it is the plane's own
// depth change between the receiver and the texel's centre, nothing tuned.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class AdaptiveBias final : public ShadowMapTechnique {
  public:
    static ParamTable params() { return shadowMapParams(DepthPrecision::params()); }
    explicit AdaptiveBias(const ParamValues& v) : ShadowMapTechnique(v), precision_(v) {}
    const char* glsl() const override { return shaders::adaptive_bias_glsl; }
    std::string shaderDefines() const override { return precision_.defines(depthBits()); }

  private:
    DepthPrecision precision_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(AdaptiveBias, "adaptive-bias",
                      "adaptive depth bias (Dou et al. 2014): the tangent plane's depth where the "
                      "light's ray through the texel's centre meets it, less the depth precision");

}  // namespace so
