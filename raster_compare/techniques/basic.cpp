// basic: the plain depth compare, no bias at all. Lit where the receiver's light-space depth is
// at most the stored depth. Shows acne wherever depth quantisation or the texel footprint puts
// the receiver behind its own stored surface.
//
// Parameters: only the common ones (resolution, depth_format).
#include "raster_compare/technique.h"

namespace so {
namespace {
class Basic final : public ShadowTechnique {
    std::string name() const override { return "basic"; }
    std::string summary() const override { return "plain depth compare, no bias"; }
    std::vector<ParamSpec> ownParams() const override { return {}; }
    std::string shaderDefines(const ParamValues&) const override { return ""; }
};
}  // namespace
const ShadowTechnique& basicTechnique() {
    static const Basic t;
    return t;
}
}  // namespace so
