// normal-offset: the lookup point moves along the geometric normal by
// k * texel * (1 - n.l) before it is projected into the map (../shared/notes/formulas.md), plus
// an optional small constant bias.
//
// | parameter | default | range   | meaning                              |
// |-----------|---------|---------|--------------------------------------|
// | k         | 1.5     | 0..100  | offset along the normal, texels       |
// | bias      | 0.1     | 0..1000 | constant bias, texels                 |
#include "raster_compare/technique.h"

namespace so {
namespace {
class NormalOffset final : public ShadowTechnique {
    std::string name() const override { return "normal-offset"; }
    std::string summary() const override {
        return "lookup moved along the normal by k texels (1 - n.l)";
    }
    std::vector<ParamSpec> ownParams() const override {
        return {{"k", 1.5, 0.0, 100.0, false, "offset along the normal in texels"},
                {"bias", 0.1, 0.0, 1000.0, false, "constant bias in texels"}};
    }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define NORMAL_OFFSET_K " + std::to_string(p.at("k")) + "\n#define BIAS_CONSTANT " +
               std::to_string(p.at("bias")) + "\n";
    }
};
}  // namespace
const ShadowTechnique& normalOffsetTechnique() {
    static const NormalOffset t;
    return t;
}
}  // namespace so
