// evsm: exponential variance shadow maps. VSM on exponentially warped depths, a positive warp
// exp(c_pos t) and a negative one -exp(-c_neg t); the lit fraction is the smaller of the two
// Chebyshev bounds, with the same bleeding reduction as vsm. 2 c_pos <= 88 keeps exp(2 c_pos t)
// a float.
#include <cmath>

#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Evsm final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "Lauritzen and McCool, \"Layered Variance Shadow Maps\", Graphics Interface 2008, "
            "section 4 (exponential warps of VSM)",
            Fidelity::Variant,
            {"warp exponents, blur radius and bleeding reduction are defaults chosen here",
             "bleeding reduction by linstep as in vsm (GPU Gems 3 ch. 8), applied to both bounds"}};
    }
    static ParamTable params() {
        return shadowMapParams(withBiasAxis(
            {{"blur", 2, 0, 16, true, "Gaussian radius in texels (sigma = blur / 2)"},
             {"c_pos", 40.0, 1.0, 42.0, false, "positive exponent"},
             {"c_neg", 5.0, 1.0, 42.0, false, "negative exponent"},
             {"min_variance", 1e-6, 0.0, 0.01, false, "variance floor, before the warp"},
             {"bleed_reduction", 0.2, 0.0, 0.99, false, "light-bleeding cut-off"}},
            "none"));
    }
    explicit Evsm(const ParamValues& v)
        : ShadowMapTechnique(v),
          blur_(v.integer("blur")),
          cPos_(v.real("c_pos")),
          cNeg_(v.real("c_neg")),
          minVariance_(v.real("min_variance")),
          bleedReduction_(v.real("bleed_reduction")) {}
    MapStorage storage() const override { return MapStorage::Moments; }
    const char* glsl() const override { return shaders::evsm_glsl; }
    std::string shaderDefines() const override {
        return glslDefine("EVSM_CPOS", cPos_) + glslDefine("EVSM_CNEG", cNeg_) +
               glslDefine("MIN_VARIANCE", minVariance_) +
               glslDefine("BLEED_REDUCTION", bleedReduction_);
    }
    int blurRadius() const override { return blur_; }
    std::array<float, 4> farMoments() const override {
        const double a = std::exp(cPos_), b = -std::exp(-cNeg_);
        return {float(a), float(a * a), float(b), float(b * b)};
    }

  private:
    int blur_;
    double cPos_, cNeg_, minVariance_, bleedReduction_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(
    Evsm, "evsm",
    "exponential variance shadow maps: VSM on exp(c_pos t) and -exp(-c_neg t), the smaller bound");

}  // namespace so
