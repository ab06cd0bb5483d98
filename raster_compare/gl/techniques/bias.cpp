// bias: a constant depth bias, in texels at the receiver: lit where receiver depth - bias <= stored
// depth.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Bias final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        return shadowMapParams(
            {{"bias", 1.0, 0.0, 1000.0, false, "constant bias in texels at the receiver"}});
    }
    explicit Bias(const ParamValues& v) : ShadowMapTechnique(v), biasTexels_(v.real("bias")) {}
    const char* glsl() const override { return shaders::bias_glsl; }
    std::string shaderDefines() const override { return glslDefine("BIAS_TEXELS", biasTexels_); }

  private:
    double biasTexels_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Bias, "bias",
                      "constant depth bias: lit where receiver depth - bias <= stored depth");

}  // namespace so
