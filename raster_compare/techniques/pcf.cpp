// pcf: percentage-closer filtering: the binary depth test averaged over a kernel x kernel grid of
// texels around the lookup (the tests are averaged, never the depths), with a slope-scaled bias
// times (1 + kernel / 2): the outer taps see the receiver's plane that many texels away.
//
// | parameter | default | range   | meaning                                  |
// |-----------|---------|---------|------------------------------------------|
// | kernel    | 3       | 1..15   | grid side in texels (odd)                 |
// | pattern   | 0       | 0..1    | 0: kernel x kernel grid; 1: 16-tap Poisson disk of radius
// kernel/2 | | alpha     | 1.0     | 0..100  | slope-bias factor (as slope-bias)         | | min |
// 0.1     | 0..1000 | smallest bias, texels                     | | max       | 10.0    | 0..1000 |
// largest bias, texels                      |
#include "raster_compare/technique.h"

#include "core/error.h"

namespace so {
namespace {
class Pcf final : public ShadowTechnique {
    std::string name() const override { return "pcf"; }
    std::string summary() const override {
        return "NxN grid percentage-closer filtering, compare per tap";
    }
    std::vector<ParamSpec> ownParams() const override {
        std::vector<ParamSpec> p = {{"kernel", 3, 1, 15, true, "grid side in texels, odd"},
                                    {"pattern", 0, 0, 1, true, "0: grid, 1: 16-tap Poisson disk"}};
        for (const ParamSpec& s : slopeBiasParams()) p.push_back(s);
        return p;
    }
    std::string shaderDefines(const ParamValues& p) const override {
        const int kernel = int(p.at("kernel"));
        if (kernel % 2 == 0) throwInputError("technique pcf", "kernel", "must be odd");
        return std::string(p.at("pattern") == 1.0 ? "#define POISSON\n" : "") +
               "#define PCF_RADIUS " + std::to_string(kernel / 2) + "\n" + slopeBiasDefines(p);
    }
};
}  // namespace
const ShadowTechnique& pcfTechnique() {
    static const Pcf t;
    return t;
}
}  // namespace so
