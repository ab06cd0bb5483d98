// msm: moment shadow maps (Peters and Klein, "Moment Shadow Mapping", I3D 2015), the Hamburger
// variant with four moments. The map stores (t, t^2, t^3, t^4) of the normalised linear depth in
// float32, blurred like VSM's; the lookup biases the filtered moments towards (0.5, 0.5, 0.5, 0.5)
// by `moment_bias` (against the round-off of a nearly singular Hankel matrix), solves for the
// three-point distribution that matches them (a Cholesky factorisation and a quadratic's roots)
// and takes its sharpest lower bound on the lit fraction. Less light bleeding than VSM where
// occluders overlap at different depths, at twice the storage of VSM's two moments; with
// `bleed_reduction` like VSM's.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Msm final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "Peters and Klein, \"Moment Shadow Mapping\", I3D 2015, algorithm 3 (Hamburger 4MSM) "
            "and section 5.1 (moment bias 3e-5 for 32-bit floats)",
            Fidelity::Variant,
            {"moments stored as 32-bit floats without the paper's optimised 16-bit quantisation",
             "the Gaussian blur radius is a default chosen here",
             "bleeding reduction (linstep, as vsm) added on top of the bound"}};
    }
    static ParamTable params() {
        return shadowMapParams(withBiasAxis(
            {{"blur", 2, 0, 16, true, "Gaussian radius in texels (sigma = blur / 2)"},
             {"moment_bias", 3e-5, 0.0, 0.1, false,
              "weight of (0.5, 0.5, 0.5, 0.5) mixed into the moments (float32: about 3e-5)"},
             {"bleed_reduction", 0.0, 0.0, 0.99, false, "light-bleeding cut-off"}},
            "none"));
    }
    explicit Msm(const ParamValues& v)
        : ShadowMapTechnique(v),
          blur_(v.integer("blur")),
          momentBias_(v.real("moment_bias")),
          bleedReduction_(v.real("bleed_reduction")) {}
    MapStorage storage() const override { return MapStorage::Moments; }
    const char* glsl() const override { return shaders::msm_glsl; }
    std::string shaderDefines() const override {
        return glslDefine("MOMENT_BIAS", momentBias_) +
               glslDefine("BLEED_REDUCTION", bleedReduction_);
    }
    int blurRadius() const override { return blur_; }
    // The far plane (t = 1) has all four moments 1.
    std::array<float, 4> farMoments() const override { return {1, 1, 1, 1}; }

  private:
    int blur_;
    double momentBias_, bleedReduction_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Msm, "msm",
                      "moment shadow maps: four moments blurred, the Hamburger 4MSM bound");

}  // namespace so
