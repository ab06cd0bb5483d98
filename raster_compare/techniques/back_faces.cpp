// back-faces: the shadow map holds the faces turned away from the light (front faces culled), so a
// lit surface is compared against the far side of its own solid, far behind it: no acne without a
// bias. Points turned away from the light are classified shadowed by n.l <= 0, as for every
// technique. For closed (watertight, outward-wound) geometry only: a single-sided occluder facing
// the light is culled and casts no shadow at all.
//
// | parameter | default | range   | meaning                        |
// |-----------|---------|---------|--------------------------------|
// | bias      | 0.0     | 0..1000 | constant bias, texels           |
#include <epoxy/gl.h>

#include "raster_compare/technique.h"

namespace so {
namespace {
class BackFaces final : public ShadowTechnique {
    std::string name() const override { return "back-faces"; }
    std::string summary() const override {
        return "back faces in the map (front-face culling), n.l <= 0 is shadow";
    }
    std::vector<ParamSpec> ownParams() const override {
        return {{"bias", 0.0, 0.0, 1000.0, false, "constant bias in texels"}};
    }
    std::string shaderDefines(const ParamValues& p) const override {
        return "#define BIAS_CONSTANT " + std::to_string(p.at("bias")) + "\n";
    }
    void beginShadowPass(const ParamValues&) const override {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
    }
    void endShadowPass(const ParamValues&) const override { glDisable(GL_CULL_FACE); }
};
}  // namespace
const ShadowTechnique& backFacesTechnique() {
    static const BackFaces t;
    return t;
}
}  // namespace so
