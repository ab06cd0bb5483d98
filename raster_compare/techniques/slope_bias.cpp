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
    std::vector<ParamSpec> ownParams() const override {
        return {{"alpha", 1.0, 0.0, 100.0, false, "slope factor"},
                {"min", 0.1, 0.0, 1000.0, false, "smallest bias in texels"},
                {"max", 10.0, 0.0, 1000.0, false, "largest bias in texels"}};
    }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define BIAS_SLOPE_ALPHA " + std::to_string(p.at("alpha")) +
               "\n#define BIAS_SLOPE_MIN " + std::to_string(p.at("min")) +
               "\n#define BIAS_SLOPE_MAX " + std::to_string(p.at("max")) + "\n";
    }
};
}  // namespace
const ShadowTechnique& slopeBiasTechnique() {
    static const SlopeBias t;
    return t;
}
}  // namespace so
