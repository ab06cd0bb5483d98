// hw-pcf: the sampler's own depth comparison with GL_LINEAR filtering (sampler2DShadow /
// samplerCubeShadow): on most implementations a bilinear 2x2 PCF, but GL leaves the filter to the
// implementation, which is why it is a technique of its own rather than a pcf setting
// (../shared/notes/gl-headless.md). Same slope bias as slope-bias, applied to the reference depth.
//
// | parameter | default | range   | meaning                  |
// |-----------|---------|---------|--------------------------|
// | alpha     | 1.0     | 0..100  | slope-bias factor        |
// | min       | 0.1     | 0..1000 | smallest bias, texels    |
// | max       | 10.0    | 0..1000 | largest bias, texels     |
#include "raster_compare/technique.h"

namespace so {
namespace {
class HwPcf final : public ShadowTechnique {
    std::string name() const override { return "hw-pcf"; }
    std::string summary() const override {
        return "the sampler's GL_LINEAR depth compare (driver-defined filter)";
    }
    std::vector<ParamSpec> ownParams() const override { return slopeBiasParams(); }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define HW_PCF\n" + slopeBiasDefines(p);
    }
    bool hardwareCompare() const override { return true; }
};
}  // namespace
const ShadowTechnique& hwPcfTechnique() {
    static const HwPcf t;
    return t;
}
}  // namespace so
