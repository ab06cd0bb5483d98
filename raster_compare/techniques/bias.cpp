// bias: a constant depth bias: lit where receiver depth - bias <= stored depth.
//
// | parameter | default | range   | meaning                                    |
// |-----------|---------|---------|--------------------------------------------|
// | bias      | 1.0     | 0..1000 | constant bias, in texels at the receiver    |
#include "raster_compare/technique.h"

namespace so {
namespace {
class Bias final : public ShadowTechnique {
    std::string name() const override { return "bias"; }
    std::string summary() const override { return "constant depth bias"; }
    std::vector<ParamSpec> ownParams() const override {
        return {{"bias", 1.0, 0.0, 1000.0, false, "constant bias in texels at the receiver"}};
    }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define BIAS_CONSTANT " + std::to_string(p.at("bias")) + "\n";
    }
};
}  // namespace
const ShadowTechnique& biasTechnique() {
    static const Bias t;
    return t;
}
}  // namespace so
