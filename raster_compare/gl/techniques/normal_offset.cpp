// normal-offset: the lookup point moves along the geometric normal by k * texel * (1 - n.l) before
// it is projected into the map (Holbert, "Normal Offset Shadows", GDC 2011), plus an optional small
// constant bias.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class NormalOffset final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        return shadowMapParams({{"k", 1.5, 0.0, 100.0, false, "offset along the normal in texels"},
                                {"bias", 0.1, 0.0, 1000.0, false, "constant bias in texels"}});
    }
    explicit NormalOffset(const ParamValues& v)
        : ShadowMapTechnique(v), kTexels_(v.real("k")), biasTexels_(v.real("bias")) {}
    const char* glsl() const override { return shaders::normal_offset_glsl; }
    std::string shaderDefines() const override {
        return glslDefine("NORMAL_OFFSET_TEXELS", kTexels_) +
               glslDefine("BIAS_TEXELS", biasTexels_);
    }

  private:
    double kTexels_, biasTexels_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(NormalOffset, "normal-offset",
                      "lookup moved along the normal by k texels (1 - n.l)");

}  // namespace so
