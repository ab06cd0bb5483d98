// bias=texel-plane: the receiver's plane from its screen-space derivatives (Isidoro, "Shadow
// Mapping: GPU-based Tips and Techniques", GDC 2006: where the pixels to its right and above fall
// in the map and how deep they lie, the chain rule through the map's projection), compared at the
// centre of the texel each tap reads (Dou, Yan, Kerzner, Dai, Wyman, "Adaptive Depth Bias for
// Shadow Maps", JCGT 3(4) 2014: the adaptive offset), where the map sampled what it holds: there a
// receiver that is its own occluder has exactly the depth the map stored, so no slope factor is
// tuned. What is left is the depth buffer's rounding (`epsilon`, DepthPrecision). This was
// `receiver-plane` before issue 63, which made that name Isidoro's form with its margin. The
// derivatives see neighbouring pixels: at a triangle's edge or a silhouette they span two surfaces
// (adaptive takes the plane from the geometric normal instead).
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class TexelPlaneDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 9;  // bias=9 means it, fixed once given
    static ParamTable params() { return DepthPrecision::params(); }
    static Provenance provenance() {
        return {
            "Dou, Yan, Kerzner, Dai, Wyman, \"Adaptive Depth Bias for Shadow Maps\", JCGT 3(4) "
            "2014 (I3D 2014): AdaptiveBias = AdaptiveOffset + AdaptiveEpsilon",
            Fidelity::Variant,
            {"the receiver's plane from the pixel's screen-space derivatives (Isidoro GDC "
             "2006), not the fragment's normal: at an edge or a silhouette it spans two "
             "surfaces"}};
    }
    explicit TexelPlaneDepthBias(const ParamValues& v) : precision_(v) {}
    const char* glsl() const override { return shaders::texel_plane_bias_glsl; }
    std::string defines(int depthBits) const override {
        return precision_.defines(depthBits) + "#define SCREEN_DERIVATIVES\n";
    }

  private:
    DepthPrecision precision_;
};

}  // namespace

SO_REGISTER_BIAS(TexelPlaneDepthBias, "texel-plane",
                 "the depth gradient from screen-space derivatives (Isidoro 2006), compared at "
                 "each tap's texel centre (Dou et al. 2014), less the depth precision");

}  // namespace so
