// esm: exponential shadow maps. The map stores exp(c t) of the normalised linear depth, blurred;
// the lit fraction is clamp(exp(-c t_receiver) * E[exp(c t)], 0, 1).
//
// | parameter | default | range  | meaning                                        |
// |-----------|---------|--------|------------------------------------------------|
// | blur      | 2       | 0..16  | Gaussian radius in texels                       |
// | c         | 80      | 1..88  | exponent (88 is the float limit of exp(c))      |
#include <cmath>

#include "raster_compare/technique.h"

namespace so {
namespace {
class Esm final : public ShadowTechnique {
    std::string name() const override { return "esm"; }
    std::string summary() const override { return "exponential shadow maps"; }
    std::vector<ParamSpec> ownParams() const override {
        return {{"blur", 2, 0, 16, true, "Gaussian radius in texels"},
                {"c", 80.0, 1.0, 88.0, false, "exponent"}};
    }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define ESM\n#define ESM_C " + std::to_string(p.at("c")) + "\n";
    }
    std::array<float, 4> farMoments(const ParamValues& p) const override {
        return {float(std::exp(p.at("c"))), 0, 0, 0};
    }
    bool filtered() const override { return true; }
    int blurRadius(const ParamValues& p) const override { return int(p.at("blur")); }
};
}  // namespace
const ShadowTechnique& esmTechnique() {
    static const Esm t;
    return t;
}
}  // namespace so
