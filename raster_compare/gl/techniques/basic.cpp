// basic: one depth compare at the receiver's own texel, with no bias by default: lit where the
// receiver's light-space depth is at most the stored depth, which shows acne wherever depth
// quantisation or the texel footprint puts the receiver behind its own stored surface. Any bias of
// the axis (`bias=NAME`, biases/) applies; the bias techniques are names for it
// (slope-bias = basic:bias=slope, receiver-plane = basic:bias=receiver-plane, ...).
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Basic final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "Williams, \"Casting Curved Shadows on Curved Surfaces\", SIGGRAPH 1978: one depth "
            "comparison at the receiver's texel",
            Fidelity::Faithful};
    }
    static ParamTable params() { return shadowMapParams(withBiasAxis({}, "none")); }
    explicit Basic(const ParamValues& v) : ShadowMapTechnique(v) {}
    const char* glsl() const override { return shaders::basic_glsl; }
};

}  // namespace

SO_REGISTER_TECHNIQUE(
    Basic, "basic",
    "one depth compare at the receiver's texel, with the bias it is given (none by default)");

}  // namespace so
