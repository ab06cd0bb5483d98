// bias=back-faces: the shadow map holds the faces turned away from the light (front faces culled),
// so a lit surface is compared against the far side of its own solid, far behind it: no acne
// without a bias. Points turned away from the light are classified shadowed by n.l <= 0, as for
// every technique. For closed (watertight, outward-wound) geometry only: a single-sided occluder
// facing the light is culled and casts no shadow at all. Plus a constant bias (back_depth_texels).
#include <epoxy/gl.h>

#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"

namespace so {
namespace {

class BackFacesDepthBias final : public DepthBias {
  public:
    static constexpr int kNumber = 5;  // bias=5 means it, fixed once given
    static ParamTable params() {
        return {{"back_depth_texels", 0.0, 0.0, 1000.0, false, "constant bias in texels"}};
    }
    static Provenance provenance() {
        return {
            "Wang, Molnar, \"Second-Depth Shadow Mapping\", UNC TR94-019, 1994: the map "
            "holds the faces turned away from the light (front faces culled)",
            Fidelity::Variant,
            {"the nearest back face (front-face culling), not the second depth layer: the same "
             "for closed meshes only",
             "plus a constant bias (back_depth_texels, 0 by default)"}};
    }
    explicit BackFacesDepthBias(const ParamValues& v) : texels_(v.real("back_depth_texels")) {}
    // The shader is the constant bias's.
    const char* glsl() const override { return shaders::constant_bias_glsl; }
    std::string defines(int) const override { return glslDefine("CONSTANT_TEXELS", texels_); }
    void beginMapPass() const override {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
    }
    void endMapPass() const override { glDisable(GL_CULL_FACE); }

  private:
    double texels_;
};

}  // namespace

SO_REGISTER_BIAS(BackFacesDepthBias, "back-faces",
                 "back faces in the map (front-face culling), then a constant bias; closed meshes "
                 "only: a single-sided occluder casts nothing");

}  // namespace so
