// pcf: percentage-closer filtering: the binary depth test averaged over a kernel x kernel grid of
// texels around the lookup (the tests are averaged, never the depths), or over a 16-tap Poisson
// disk of radius kernel / 2 + 1/2, with the slope-scaled bias of slope-bias times
// (1 + kernel / 2): the outer taps see the receiver's plane that many texels away.
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_map.h"

namespace so {
namespace {

class Pcf final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        ParamTable own = {
            {"kernel", 3, 1, 15, true, "grid side in texels, odd", {1, 3, 5, 7, 9, 11, 13, 15}},
            methodParam("pattern", 0, {"grid", "poisson"},
                        "grid: kernel x kernel taps; poisson: a 16-tap Poisson disk")};
        for (const ParamSpec& s : SlopeBias::params()) own.push_back(s);
        return shadowMapParams(own);
    }
    explicit Pcf(const ParamValues& v)
        : ShadowMapTechnique(v),
          radius_(v.integer("kernel") / 2),
          poisson_(v.integer("pattern") == 1),
          bias_(v) {}
    const char* glsl() const override { return shaders::pcf_glsl; }
    std::string shaderDefines() const override {
        return std::string(poisson_ ? "#define POISSON\n" : "") + "#define PCF_RADIUS " +
               std::to_string(radius_) + "\n" + bias_.defines();
    }

  private:
    int radius_;  // texels from the centre tap
    bool poisson_;
    SlopeBias bias_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Pcf, "pcf",
                      "percentage-closer filtering: the depth test averaged over a kernel x kernel "
                      "grid or 16 Poisson-disk taps, the slope bias times (1 + kernel / 2)");

}  // namespace so
