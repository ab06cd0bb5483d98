// polygon-offset: the fixed-function glPolygonOffset(factor, units) applied while rendering the
// shadow map, no bias in the shader (its GLSL is basic's). Kept apart from slope-bias because GL
// leaves the slope it uses and the size of a "unit" to the implementation
// (GL 4.5 core, 14.6.5: offset = factor * DZ + r * units, DZ and r implementation-defined).
#include <epoxy/gl.h>

#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class PolygonOffset final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        return shadowMapParams({{"factor", 1.5, -100.0, 100.0, false, "glPolygonOffset factor"},
                                {"units", 4.0, -1e6, 1e6, false, "glPolygonOffset units"}});
    }
    explicit PolygonOffset(const ParamValues& v)
        : ShadowMapTechnique(v), factor_(float(v.real("factor"))), units_(float(v.real("units"))) {}
    const char* glsl() const override { return shaders::basic_glsl; }
    void beginMapPass() const override {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(factor_, units_);
    }
    void endMapPass() const override { glDisable(GL_POLYGON_OFFSET_FILL); }

  private:
    float factor_, units_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(PolygonOffset, "polygon-offset",
                      "fixed-function glPolygonOffset in the shadow pass (driver-defined units)");

}  // namespace so
