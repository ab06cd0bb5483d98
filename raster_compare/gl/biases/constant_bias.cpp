// bias=constant: a constant depth bias, in texels at the receiver: lit where receiver depth -
// bias <= stored depth (the `bias` technique).
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"

namespace so {
namespace {

class ConstantDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 1;  // bias=1 means it, fixed once given
    static ParamTable params() {
        return {
            {"depth_texels", 1.0, 0.0, 1000.0, false, "constant bias in texels at the receiver"}};
    }
    static Provenance provenance() {
        return {
            "Reeves, Salesin, Cook, \"Rendering Antialiased Shadows with Depth Maps\", "
            "SIGGRAPH 1987: a constant bias subtracted before the comparison",
            Fidelity::Variant,
            {"the bias in texels of the map at the receiver (depth_texels times the texel's "
             "world size there), not one fixed depth for the scene"}};
    }
    explicit ConstantDepthBias(const ParamValues& v) : texels_(v.real("depth_texels")) {}
    const char* glsl() const override { return shaders::constant_bias_glsl; }
    std::string defines(int) const override { return glslDefine("CONSTANT_TEXELS", texels_); }

  private:
    double texels_;
};

}  // namespace

SO_REGISTER_BIAS(ConstantDepthBias, "constant",
                 "constant depth bias: lit where receiver depth - depth_texels <= stored depth");

}  // namespace so
