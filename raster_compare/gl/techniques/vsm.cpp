// vsm: variance shadow maps. The map stores the moments (t, t^2) of the normalised linear depth,
// blurred by a separable Gaussian (sigma = blur / 2); the lookup bilinearly filters them and takes
// the one-sided Chebyshev bound p_max = s^2 / (s^2 + (t - mu)^2) as the lit fraction. Light
// bleeding appears where occluders overlap at different depths; the reduction rescales p_max with
// linstep(bleed_reduction, 1, p_max) (Donnelly and Lauritzen,
// "Variance Shadow Maps", I3D 2006; the reduction from GPU Gems 3, chapter 8).
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class Vsm final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "Donnelly and Lauritzen, \"Variance Shadow Maps\", I3D 2006, and the light-bleeding "
            "reduction of GPU Gems 3 chapter 8 (Lauritzen, \"Summed-Area Variance Shadow Maps\")",
            Fidelity::Faithful};
    }
    static ParamTable params() {
        return shadowMapParams(withBiasAxis(
            {{"blur", 2, 0, 16, true, "Gaussian radius in texels (sigma = blur / 2)"},
             {"min_variance", 1e-6, 0.0, 0.01, false, "variance floor (normalised depth^2)"},
             {"bleed_reduction", 0.2, 0.0, 0.99, false, "light-bleeding cut-off"}},
            "none"));
    }
    explicit Vsm(const ParamValues& v)
        : ShadowMapTechnique(v),
          blur_(v.integer("blur")),
          minVariance_(v.real("min_variance")),
          bleedReduction_(v.real("bleed_reduction")) {}
    MapStorage storage() const override { return MapStorage::Moments; }
    const char* glsl() const override { return shaders::vsm_glsl; }
    std::string shaderDefines() const override {
        return glslDefine("MIN_VARIANCE", minVariance_) +
               glslDefine("BLEED_REDUCTION", bleedReduction_);
    }
    int blurRadius() const override { return blur_; }

  private:
    int blur_;
    double minVariance_, bleedReduction_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Vsm, "vsm",
                      "variance shadow maps: moments (t, t^2) blurred, the Chebyshev bound, "
                      "linstep(bleed_reduction, 1, p)");

}  // namespace so
