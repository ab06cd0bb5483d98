// hw-pcf: the sampler's own depth comparison with GL_LINEAR filtering (sampler2DShadow /
// samplerCubeShadow): on most implementations a bilinear 2x2 PCF, but GL leaves the filter to the
// implementation, which is why it is a technique of its own rather than a pcf setting
// (GL 4.5 core, 8.22: how a depth-compare lookup is filtered is up to the implementation). The
// reference depth is its bias's (`bias`, biases/; by default slope-bias's).
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class HwPcf final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "OpenGL 4.5 core specification, section 8.22 (texture comparison with GL_LINEAR "
            "filtering: the driver's own percentage-closer filter)",
            Fidelity::Faithful};
    }
    static ParamTable params() { return shadowMapParams(withBiasAxis({}, "slope")); }
    explicit HwPcf(const ParamValues& v) : ShadowMapTechnique(v) {}
    MapStorage storage() const override { return MapStorage::DepthHardwareCompare; }
    const char* glsl() const override { return shaders::hw_pcf_glsl; }
};

}  // namespace

SO_REGISTER_TECHNIQUE(HwPcf, "hw-pcf",
                      "the sampler's GL_LINEAR depth compare (driver-defined filter)");

}  // namespace so
