// slope-bias: a bias that grows with the receiver's slope to the light, computed in the shader:
// eps = clamp(alpha * tan(acos(n.l)), min, max) texels (../shared/notes/formulas.md). Within one
// texel a receiver tilted by theta spans tan(theta) texels of depth, which is what causes acne.
//
// | parameter | default | range   | meaning                          |
// |-----------|---------|---------|----------------------------------|
// | alpha     | 1.0     | 0..100  | slope factor                     |
// | min       | 0.1     | 0..1000 | smallest bias, texels            |
// | max       | 10.0    | 0..1000 | largest bias, texels             |
#include "raster_compare/technique.h"

namespace so {
namespace {
class SlopeBias final : public ShadowTechnique {
    std::string name() const override { return "slope-bias"; }
    std::string summary() const override {
        return "slope-scaled bias clamp(alpha tan(acos(n.l)), min, max)";
    }
    std::vector<ParamSpec> ownParams() const override { return slopeBiasParams(); }
    std::string shaderDefines(const ParamValues& p) const override { return slopeBiasDefines(p); }
};
}  // namespace
const ShadowTechnique& slopeBiasTechnique() {
    static const SlopeBias t;
    return t;
}
}  // namespace so
