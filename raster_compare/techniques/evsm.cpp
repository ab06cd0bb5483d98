// evsm: exponential variance shadow maps. VSM on exponentially warped depths, a positive warp
// exp(c_pos t) and a negative one -exp(-c_neg t); the lit fraction is the smaller of the two
// Chebyshev bounds, with the same bleeding reduction as vsm.
//
// | parameter       | default | range   | meaning                                 |
// |-----------------|---------|---------|-----------------------------------------|
// | blur            | 2       | 0..16   | Gaussian radius in texels                |
// | c_pos           | 40      | 1..42   | positive exponent (2 c_pos <= 88)        |
// | c_neg           | 5       | 1..42   | negative exponent                        |
// | min_variance    | 1e-6    | 0..0.01 | variance floor, before the warp          |
// | bleed_reduction | 0.2     | 0..0.99 | light-bleeding cut-off                   |
#include <cmath>

#include "raster_compare/technique.h"

namespace so {
namespace {
class Evsm final : public ShadowTechnique {
    std::string name() const override { return "evsm"; }
    std::string summary() const override {
        return "exponential variance shadow maps (positive and negative warps)";
    }
    std::vector<ParamSpec> ownParams() const override {
        return {{"blur", 2, 0, 16, true, "Gaussian radius in texels"},
                {"c_pos", 40.0, 1.0, 42.0, false, "positive exponent"},
                {"c_neg", 5.0, 1.0, 42.0, false, "negative exponent"},
                {"min_variance", 1e-6, 0.0, 0.01, false, "variance floor"},
                {"bleed_reduction", 0.2, 0.0, 0.99, false, "light-bleeding cut-off"}};
    }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define EVSM\n#define EVSM_CPOS " + std::to_string(p.at("c_pos")) +
               "\n#define EVSM_CNEG " + std::to_string(p.at("c_neg")) + "\n#define MIN_VARIANCE " +
               std::to_string(p.at("min_variance")) + "\n#define BLEED_REDUCTION " +
               std::to_string(p.at("bleed_reduction")) + "\n";
    }
    std::array<float, 4> farMoments(const ParamValues& p) const override {
        const double a = std::exp(p.at("c_pos")), b = -std::exp(-p.at("c_neg"));
        return {float(a), float(a * a), float(b), float(b * b)};
    }
    bool filtered() const override { return true; }
    int blurRadius(const ParamValues& p) const override { return int(p.at("blur")); }
};
}  // namespace
const ShadowTechnique& evsmTechnique() {
    static const Evsm t;
    return t;
}
}  // namespace so
