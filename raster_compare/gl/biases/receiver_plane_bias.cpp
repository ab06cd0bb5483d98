// bias=receiver-plane: receiver plane depth bias (Isidoro, "Shadow Mapping: GPU-based Tips and
// Techniques", GDC 2006) with the fractional-sampling-error margin as TheRealMJP/Shadows writes it
// (Shadows/Mesh.hlsl at 338290a, SampleShadowMapFixedSizePCF, GridPCF, RandomDiscPCF; Unity's PCSS
// and Bevy PR 10188 write it the same way). The receiver's depth gradient in the map, per texel,
// from its screen-space derivatives (where the pixels to its right and above fall in the map and
// how deep they lie: Mesh.hlsl:102-109); each tap compares the receiver's depth plus the plane's
// rise to the tap (:190-193), less a static margin for the tap's texel sampling the plane
// elsewhere than the tap's point: the plane's rise over one texel along each axis (:131). MJP caps
// it at 0.01 of the map's window depth (:132), against a near edge-on receiver lifting off its
// occluder; here the cap is a parameter and off by default: under a grazing sun the plane rises
// more than that over a texel and the capped margin is acne (issue 63's criterion, measured in
// the provenance's deviation). The margin grows with the slope, so the filter's width needs no
// bias of its own.
// The derivatives see neighbouring pixels: at a triangle's edge or a silhouette they span two
// surfaces.
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class ReceiverPlaneDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 6;  // bias=6 means it, fixed once given
    static ParamTable params() {
        ParamTable table = DepthPrecision::params();
        table.insert(
            table.begin(),
            {{"margin_texels", 1.0, 0.0, 100.0, false,
              "fractional sampling error: the plane's rise over this many texels along each "
              "map axis (Mesh.hlsl:131: 1; 2 in its GatherCmp PCF, :542)"},
             {"margin_cap", 1.0, 0.0, 1.0, false,
              "the most margin, in the map's window depth [0, 1] from near to far; 1: no cap "
              "(Mesh.hlsl:132 caps at 0.01, which leaves acne under a grazing light)"}});
        return table;
    }
    static Provenance provenance() {
        return {
            "Isidoro, \"Shadow Mapping: GPU-based Tips and Techniques\", GDC 2006; the margin "
            "as TheRealMJP/Shadows 338290a, Shadows/Mesh.hlsl:102-109, 125-132, 190-193 "
            "(SampleShadowMapFixedSizePCF)",
            Fidelity::Variant,
            {"depths compared as linear distances along the map's view axis: on perspective "
             "and cube maps the plane is extrapolated to first order in the tap's offset "
             "where MJP's window depth (directional cascades only) is exact",
             "the gradient from a texel-long step along the pixel's derivatives, not the "
             "pixel's step itself (the same plane; no curvature of a perspective map)",
             "taps point-sampled as the filter reads them (pcf, pcss), where MJP compares "
             "2x2 in hardware (SampleCmpLevelZero)",
             "the margin uncapped by default (margin_cap=1; Mesh.hlsl:132 caps it at 0.01 of "
             "the window depth): under a sun 0.23 degrees above a floor the capped margin left "
             "acne 0.39 (tests/data/grazing_bias, 160x120)",
             "plus the depth buffer's rounding (epsilon, as adaptive and texel-plane): a "
             "perspective map's window depth rounds to more than the fractional error where "
             "the receiver faces the light (contact_box's point light: acne 0.34 without it)"}};
    }
    explicit ReceiverPlaneDepthBias(const ParamValues& v)
        : marginTexels_(v.real("margin_texels")), marginCap_(v.real("margin_cap")), precision_(v) {}
    const char* glsl() const override { return shaders::receiver_plane_bias_glsl; }
    std::string defines(int depthBits) const override {
        return precision_.defines(depthBits) + "#define SCREEN_DERIVATIVES\n" +
               glslDefine("MARGIN_TEXELS", marginTexels_) + glslDefine("MARGIN_CAP", marginCap_);
    }

  private:
    double marginTexels_, marginCap_;
    DepthPrecision precision_;
};

}  // namespace

SO_REGISTER_BIAS(ReceiverPlaneDepthBias, "receiver-plane",
                 "receiver plane depth bias (Isidoro 2006): each tap at the receiver's depth plus "
                 "the plane's rise to it (screen-space derivatives), less the plane's rise over a "
                 "texel (TheRealMJP/Shadows' margin, uncapped)");

}  // namespace so
