// esm: exponential shadow maps. The map stores exp(c t) of the normalised linear depth, blurred;
// the lit fraction is clamp(exp(-c t_receiver) * E[exp(c t)], 0, 1). c up to 88: exp(88) is near
// the largest float.
#include <cmath>

#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Esm final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "Annen, Mertens, Seidel, Flerackers and Kautz, \"Exponential Shadow Maps\", Graphics "
            "Interface 2008, section 3",
            Fidelity::Variant,
            {"the exponent c and the Gaussian blur radius are defaults chosen here (c = 80, blur 2 "
             "texels)",
             "the map holds depth normalised over the light's range, linear in eye distance",
             "the estimate is clamped to [0, 1] where the paper leaves over-darkening to c"}};
    }
    static ParamTable params() {
        return shadowMapParams(
            withBiasAxis({{"blur", 2, 0, 16, true, "Gaussian radius in texels (sigma = blur / 2)"},
                          {"c", 80.0, 1.0, 88.0, false, "exponent"}},
                         "none"));
    }
    explicit Esm(const ParamValues& v)
        : ShadowMapTechnique(v), blur_(v.integer("blur")), c_(v.real("c")) {}
    MapStorage storage() const override { return MapStorage::Moments; }
    const char* glsl() const override { return shaders::esm_glsl; }
    std::string shaderDefines() const override { return glslDefine("ESM_C", c_); }
    int blurRadius() const override { return blur_; }
    std::array<float, 4> farMoments() const override { return {float(std::exp(c_)), 0, 0, 0}; }

  private:
    int blur_;
    double c_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(
    Esm, "esm",
    "exponential shadow maps: exp(c t) blurred, lit = clamp(exp(-c t) E[exp(c t)], 0, 1)");

}  // namespace so
