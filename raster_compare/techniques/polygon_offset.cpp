// polygon-offset: the fixed-function glPolygonOffset(factor, units) applied while rendering the
// shadow map, no bias in the shader. Kept apart from slope-bias because GL leaves the slope it
// uses and the size of a "unit" to the implementation (../shared/notes/gl-headless.md).
//
// | parameter | default | range      | meaning                       |
// |-----------|---------|------------|-------------------------------|
// | factor    | 1.5     | -100..100  | glPolygonOffset factor        |
// | units     | 4.0     | -1e6..1e6  | glPolygonOffset units         |
#include <epoxy/gl.h>

#include "raster_compare/technique.h"

namespace so {
namespace {
class PolygonOffset final : public ShadowTechnique {
    std::string name() const override { return "polygon-offset"; }
    std::string summary() const override {
        return "fixed-function glPolygonOffset in the shadow pass";
    }
    std::vector<ParamSpec> ownParams() const override {
        return {{"factor", 1.5, -100.0, 100.0, false, "glPolygonOffset factor"},
                {"units", 4.0, -1e6, 1e6, false, "glPolygonOffset units"}};
    }
    std::string shaderDefines(const ParamValues&) const override { return ""; }
    void beginShadowPass(const ParamValues& p) const override {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(float(p.at("factor")), float(p.at("units")));
    }
    void endShadowPass(const ParamValues&) const override { glDisable(GL_POLYGON_OFFSET_FILL); }
};
}  // namespace
const ShadowTechnique& polygonOffsetTechnique() {
    static const PolygonOffset t;
    return t;
}
}  // namespace so
