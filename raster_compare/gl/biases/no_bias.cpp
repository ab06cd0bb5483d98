// bias=none: no bias at all; the receiver compared at its own depth (basic's default). Shows acne
// wherever depth quantisation or the texel footprint puts the receiver behind its own stored
// surface.
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"

namespace so {
namespace {

class NoDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 0;  // bias=0 means it, fixed once given
    static ParamTable params() { return {}; }
    static Provenance provenance() {
        return {
            "Williams, \"Casting Curved Shadows on Curved Surfaces\", SIGGRAPH 1978: the "
            "depth comparison with no bias",
            Fidelity::Faithful};
    }
    explicit NoDepthBias(const ParamValues&) {}
    const char* glsl() const override { return shaders::no_bias_glsl; }
};

}  // namespace

SO_REGISTER_BIAS(NoDepthBias, "none", "no bias: lit where receiver depth <= stored depth");

}  // namespace so
