// bias=normal-offset: the lookup point moves along the geometric normal by
// normal_texels * texel * (1 - n.l) before it is projected into the map (Holbert, "Normal Offset
// Shadows", GDC 2011), plus a small constant bias (normal_depth_texels).
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"

namespace so {
namespace {

class NormalOffsetDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 3;  // bias=3 means it, fixed once given
    static ParamTable params() {
        return {{"normal_texels", 1.5, 0.0, 100.0, false,
                 "offset along the normal in texels, times (1 - n.l)"},
                {"normal_depth_texels", 0.1, 0.0, 1000.0, false,
                 "constant bias in texels after the offset"}};
    }
    static Provenance provenance() {
        return {
            "after Holbert, \"Normal Offset Shadows\" (GDC 2011 poster \"Saying Goodbye to "
            "Shadow Acne\"); the (1 - n.l) scale as Unity URP Shadows.hlsl ApplyShadowBias "
            "writes it on the caster side. Ours offsets the receiver's lookup, in texels, plus "
            "a constant bias; the talk's own constants were not read",
            Fidelity::Own};
    }
    explicit NormalOffsetDepthBias(const ParamValues& v)
        : normalTexels_(v.real("normal_texels")), depthTexels_(v.real("normal_depth_texels")) {}
    const char* glsl() const override { return shaders::normal_offset_bias_glsl; }
    std::string defines(int) const override {
        return glslDefine("NORMAL_OFFSET_TEXELS", normalTexels_) +
               glslDefine("NORMAL_DEPTH_TEXELS", depthTexels_);
    }

  private:
    double normalTexels_, depthTexels_;
};

}  // namespace

SO_REGISTER_BIAS(NormalOffsetDepthBias, "normal-offset",
                 "lookup moved along the normal by normal_texels (1 - n.l) texels, then a "
                 "constant bias");

}  // namespace so
