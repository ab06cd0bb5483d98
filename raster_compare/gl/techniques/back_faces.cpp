// back-faces: the shadow map holds the faces turned away from the light (front faces culled), so a
// lit surface is compared against the far side of its own solid, far behind it: no acne without a
// bias. Points turned away from the light are classified shadowed by n.l <= 0, as for every
// technique. For closed (watertight, outward-wound) geometry only: a single-sided occluder facing
// the light is culled and casts no shadow at all. Its GLSL is bias's (a constant bias).
#include <epoxy/gl.h>

#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {
namespace {

class BackFaces final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        return shadowMapParams({{"bias", 0.0, 0.0, 1000.0, false, "constant bias in texels"}});
    }
    explicit BackFaces(const ParamValues& v) : ShadowMapTechnique(v), biasTexels_(v.real("bias")) {}
    const char* glsl() const override { return shaders::bias_glsl; }
    std::string shaderDefines() const override { return glslDefine("BIAS_TEXELS", biasTexels_); }
    void beginMapPass() const override {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
    }
    void endMapPass() const override { glDisable(GL_CULL_FACE); }

  private:
    double biasTexels_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(BackFaces, "back-faces",
                      "back faces in the map (front-face culling), n.l <= 0 is shadow; closed "
                      "meshes only: a single-sided occluder casts nothing");

}  // namespace so
