// vsm: variance shadow maps. The map stores the moments (t, t^2) of the normalised linear depth,
// blurred by a separable Gaussian; the lookup bilinearly filters them and takes the one-sided
// Chebyshev bound p_max = s^2 / (s^2 + (t - mu)^2) as the lit fraction. Light bleeding appears
// where occluders overlap at different depths; the reduction rescales p_max with
// linstep(bleed_reduction, 1, p_max) (../shared/notes/formulas.md).
//
// | parameter       | default | range   | meaning                                      |
// |-----------------|---------|---------|----------------------------------------------|
// | blur            | 2       | 0..16   | Gaussian radius in texels (sigma = blur / 2)  |
// | min_variance    | 1e-6    | 0..0.01 | variance floor (normalised depth^2)           |
// | bleed_reduction | 0.2     | 0..0.99 | light-bleeding cut-off                        |
#include "raster_compare/technique.h"

namespace so {
namespace {
class Vsm final : public ShadowTechnique {
    std::string name() const override { return "vsm"; }
    std::string summary() const override {
        return "variance shadow maps: blurred moments, Chebyshev bound";
    }
    std::vector<ParamSpec> ownParams() const override {
        return {{"blur", 2, 0, 16, true, "Gaussian radius in texels"},
                {"min_variance", 1e-6, 0.0, 0.01, false, "variance floor"},
                {"bleed_reduction", 0.2, 0.0, 0.99, false, "light-bleeding cut-off"}};
    }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define VSM\n#define MIN_VARIANCE " + std::to_string(p.at("min_variance")) +
               "\n#define BLEED_REDUCTION " + std::to_string(p.at("bleed_reduction")) + "\n";
    }
    bool filtered() const override { return true; }
    int blurRadius(const ParamValues& p) const override { return int(p.at("blur")); }
};
}  // namespace
const ShadowTechnique& vsmTechnique() {
    static const Vsm t;
    return t;
}
}  // namespace so
