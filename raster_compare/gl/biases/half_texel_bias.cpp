// bias=half-texel: a design of ours (issue 54's `oriented`, renamed in issue 63: it was written
// after Final Fantasy XVI's oriented depth bias, Square Enix, "FINAL FANTASY XVI Shadow
// Techniques", 2023, p. 28, as bevyengine/bevy 16075 cites it, without the talk being read, so it
// carries no claim to be that design). The receiver's tangent plane (its geometric normal) gives
// its depth gradient per texel along each of the map's axes; the texel a tap reads sampled that
// plane at most half a texel away along each, so the bias is the most the plane can rise over that
// distance, |g_u| / 2 + |g_v| / 2, plus the depth buffer's rounding (DepthPrecision): the least
// bias that is never acne on a plane, with no slope factor to tune. Unlike adaptive it does not
// use where the texel's centre lies, only how the plane is oriented: on a curved surface, whose
// stored texel need not lie on the receiver's tangent plane, it keeps that half-texel margin.
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class HalfTexelDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 8;  // bias=8 means it, fixed once given
    static ParamTable params() { return DepthPrecision::params(); }
    static Provenance provenance() {
        return {
            "ours: the tangent plane's gradient as adaptive takes it (Dou et al., JCGT 3(4) "
            "2014) with a half-texel margin instead of the texel centre; first written after "
            "FFXVI's oriented depth bias (Square Enix 2023), whose talk was not read",
            Fidelity::Own};
    }
    explicit HalfTexelDepthBias(const ParamValues& v) : precision_(v) {}
    const char* glsl() const override { return shaders::half_texel_bias_glsl; }
    std::string defines(int depthBits) const override { return precision_.defines(depthBits); }

  private:
    DepthPrecision precision_;
};

}  // namespace

SO_REGISTER_BIAS(HalfTexelDepthBias, "half-texel",
                 "the tangent plane's largest rise over half a texel along each map axis, plus the "
                 "depth precision (ours; was `oriented`)");

}  // namespace so
