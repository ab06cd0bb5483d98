// basic: the plain depth compare, no bias at all. Lit where the receiver's light-space depth is at
// most the stored depth. Shows acne wherever depth quantisation or the texel footprint puts the
// receiver behind its own stored surface. Parameters: only the family's (resolution, depth_format,
// fit).
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Basic final : public ShadowMapTechnique {
  public:
    static ParamTable params() { return shadowMapParams({}); }
    explicit Basic(const ParamValues& v) : ShadowMapTechnique(v) {}
    const char* glsl() const override { return shaders::basic_glsl; }
};

}  // namespace

SO_REGISTER_TECHNIQUE(Basic, "basic",
                      "plain depth compare: lit where receiver depth <= stored depth, no bias");

}  // namespace so
