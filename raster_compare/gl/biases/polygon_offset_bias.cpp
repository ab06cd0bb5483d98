// bias=polygon-offset: the fixed-function glPolygonOffset(factor, units) applied while rendering
// the shadow map, no bias in the shader. Kept apart from the slope bias because GL leaves the slope
// it uses and the size of a "unit" to the implementation (GL 4.5 core, 14.6.5: offset = factor *
// DZ + r * units, DZ and r implementation-defined). Moment maps store the fragment's own depth, not
// the offset one: with them it changes nothing.
#include <epoxy/gl.h>

#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"

namespace so {
namespace {

class PolygonOffsetDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 4;  // bias=4 means it, fixed once given
    static ParamTable params() {
        return {{"factor", 1.5, -100.0, 100.0, false, "glPolygonOffset factor"},
                {"units", 4.0, -1e6, 1e6, false, "glPolygonOffset units"}};
    }
    static Provenance provenance() {
        return {
            "OpenGL 4.5 core profile 14.6.5, glPolygonOffset(factor, units): offset = factor * "
            "DZ + r * units in the shadow pass",
            Fidelity::Faithful};
    }
    explicit PolygonOffsetDepthBias(const ParamValues& v)
        : factor_(float(v.real("factor"))), units_(float(v.real("units"))) {}
    // The shader compares as bias=none does.
    const char* glsl() const override { return shaders::no_bias_glsl; }
    void beginMapPass() const override {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(factor_, units_);
    }
    void endMapPass() const override { glDisable(GL_POLYGON_OFFSET_FILL); }

  private:
    float factor_, units_;
};

}  // namespace

SO_REGISTER_BIAS(PolygonOffsetDepthBias, "polygon-offset",
                 "fixed-function glPolygonOffset in the shadow pass (driver-defined units)");

}  // namespace so
