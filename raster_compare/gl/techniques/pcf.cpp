// pcf: percentage-closer filtering: the binary depth test averaged over a kernel x kernel grid of
// texels around the lookup (the tests are averaged, never the depths), or over a 16-tap Poisson
// disk of radius kernel / 2 + 1/2, each tap compared at the depth its bias gives (`bias`, biases/;
// by default the slope-scaled bias of slope-bias times (1 + kernel / 2): the outer taps see the
// receiver's plane that many texels away, BIAS_SPREAD). With
// temporal=on (docs/techniques.md#temporal) the same number of taps lie on a Vogel disk turned
// per pixel and frame by interleaved gradient noise, over the area of the pattern it replaces
// (the grid's square: radius (2 (kernel / 2) + 1) / sqrt(pi) texels; the Poisson disk's radius),
// and a ShadowHistory resolves them over frames.
#include <cmath>
#include <numbers>

#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/time/temporal_taps.h"

namespace so {
namespace {

class Pcf final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        ParamTable own = {
            {"kernel", 3, 1, 15, true, "grid side in texels, odd", {1, 3, 5, 7, 9, 11, 13, 15}},
            methodParam("pattern", 0, {"grid", "poisson"},
                        "grid: kernel x kernel taps; poisson: a 16-tap Poisson disk")};
        own = withBiasAxis(std::move(own), "slope");
        for (const ParamSpec& s : TemporalTaps::params()) own.push_back(s);
        return shadowMapParams(own);
    }
    explicit Pcf(const ParamValues& v)
        : ShadowMapTechnique(v),
          radius_(v.integer("kernel") / 2),
          poisson_(v.integer("pattern") == 1),
          temporal_(v) {}
    const char* glsl() const override { return shaders::pcf_glsl; }
    std::string shaderDefines() const override {
        std::string d = std::string(poisson_ ? "#define POISSON\n" : "") + "#define PCF_RADIUS " +
                        std::to_string(radius_) +
                        "\n#define BIAS_SPREAD (1.0 + float(PCF_RADIUS))\n" + temporal_.defines();
        if (!temporal_.on) return d;  // off: the defines it always had, the same shader
        const int side = 2 * radius_ + 1;
        const int taps = poisson_ ? 16 : side * side;
        const double diskTexels = poisson_ ? radius_ + 0.5 : side / std::sqrt(std::numbers::pi);
        return d + "#define PCF_TAPS " + std::to_string(taps) + "\n" +
               glslDefine("PCF_DISK_TEXELS", diskTexels);
    }
    std::optional<HistorySettings> history() const override { return temporal_.history(); }

  private:
    int radius_;  // texels from the centre tap
    bool poisson_;
    TemporalTaps temporal_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(
    Pcf, "pcf",
    "percentage-closer filtering: the depth test averaged over a kernel x kernel "
    "grid or 16 Poisson-disk taps, each at its bias (by default the slope bias times (1 + "
    "kernel / 2))");

}  // namespace so
