// bias=adaptive: adaptive depth bias (Dou, Yan, Kerzner, Dai, Wyman, "Adaptive Depth Bias for
// Shadow Maps", I3D 2014; JCGT 2015). The ray from the light through the centre of the texel a tap
// reads meets the receiver's tangent plane (from its geometric normal) at the depth the receiver
// would have stored there; that depth, less a margin for the depth buffer's precision at that
// depth (the paper's adaptive epsilon; here `epsilon` steps of the buffer's last bit,
// DepthPrecision), is compared with the map. The bias can be either sign: it is the plane's own
// depth change between the receiver and the texel's centre, nothing tuned.
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class AdaptiveDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 7;  // bias=7 means it, fixed once given
    static ParamTable params() { return DepthPrecision::params(); }
    static Provenance provenance() {
        return {
            "Dou, Yan, Kerzner, Dai, Wyman, \"Adaptive Depth Bias for Shadow Maps\", JCGT 3(4) "
            "2014 (I3D 2014): AdaptiveBias = AdaptiveOffset (the tangent plane at the "
            "texel's centre) + AdaptiveEpsilon (the depth buffer's precision, eq. 3)",
            Fidelity::Faithful};
    }
    explicit AdaptiveDepthBias(const ParamValues& v) : precision_(v) {}
    const char* glsl() const override { return shaders::adaptive_bias_glsl; }
    std::string defines(int depthBits) const override { return precision_.defines(depthBits); }

  private:
    DepthPrecision precision_;
};

}  // namespace

SO_REGISTER_BIAS(AdaptiveDepthBias, "adaptive",
                 "adaptive depth bias (Dou et al. 2014): the tangent plane's depth where the "
                 "light's ray through the tap's texel centre meets it, less the depth precision");

}  // namespace so
