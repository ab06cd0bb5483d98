// bias=slope: a bias that grows with the receiver's slope to the light,
// eps = clamp(slope_factor * tan(acos(n.l)), min, max) texels, times the filter's reach
// (BIAS_SPREAD: pcf's outer taps see the receiver's plane that many texels deeper). Within one
// texel a receiver tilted by theta spans tan(theta) texels of depth, which is what causes acne.
// Its table is SlopeBias's (shadow_map.h), which smrt and adaptive, who take no other bias, share.
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class SlopeDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 2;  // bias=2 means it, fixed once given
    static ParamTable params() { return SlopeBias::params(); }
    static Provenance provenance() {
        return {
            "the rasterizer's slope-scaled depth bias (OpenGL 4.5 core 14.6.5, glPolygonOffset "
            "factor * DZ; Direct3D 11 SlopeScaledDepthBias with DepthBiasClamp), moved into "
            "the shader as tan(acos(n.l)) texels, clamped, times the filter's reach",
            Fidelity::Own};
    }
    explicit SlopeDepthBias(const ParamValues& v) : slope_(v) {}
    const char* glsl() const override { return shaders::slope_bias_glsl; }
    std::string defines(int) const override { return slope_.defines(); }

  private:
    SlopeBias slope_;
};

}  // namespace

SO_REGISTER_BIAS(SlopeDepthBias, "slope",
                 "slope-scaled bias clamp(slope_factor tan(acos(n.l)), min, max) texels");

}  // namespace so
