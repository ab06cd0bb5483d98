// shadow-texture: shadow textures (projective texturing of an occluder image). The casters (every
// mesh but the receiver) are rendered from the light into a texture as opacity (1 where one
// covers the texel), which is projected onto the receiver: V = 1 - opacity there, filtered
// bilinearly (soft, blocky edges) or point-sampled (`filter`). Only the receiver gets a shadow:
// no self-shadowing and no shadow on other casters, by design (false lit, which the metrics
// count). Receivers behind a spot light would take a back-projected shadow; they are masked (lit).
// The receiver is a mesh index (`receiver`, as id.mesh) or the largest planar mesh. The texture is
// stored as the shadow-map family's moment map (RGBA32F, opacity in the first channel).
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/volumes/receiver_plane.h"

namespace so {
namespace {

class ShadowTexture final : public ShadowMapTechnique {
  public:
    static constexpr const char* kFamily = "shadow texture";
    static Provenance provenance() {
        return {
            "Segal, Korobkin, van Widenfelt, Foran and Haeberli, \"Fast Shadows and Lighting "
            "Effects Using Texture Mapping\", SIGGRAPH 1992 (the casters' image projected onto the "
            "receiver)",
            Fidelity::Faithful};
    }
    static ParamTable params() {
        return shadowMapParams(
            {methodParam("filter", 1, {"point", "bilinear"},
                         "bilinear lookup of the texture, or point sampling"),
             {"receiver", -1, -1, 1e6, true,
              "mesh index (as id.mesh) of the receiver; -1: the largest planar mesh"}});
    }
    explicit ShadowTexture(const ParamValues& v)
        : ShadowMapTechnique(v),
          bilinear_(v.integer("filter") == 1),
          receiver_(v.integer("receiver")) {}
    MapStorage storage() const override { return MapStorage::Moments; }
    const char* glsl() const override { return shaders::shadow_texture_glsl; }
    std::array<float, 4> farMoments() const override { return {0, 0, 0, 0}; }  // no caster
    bool bilinearMap() const override { return bilinear_; }
    int receiverMesh(const GpuScene& scene) const override {
        return findReceiver(scene.scene(), scene.frame(), receiver_, "shadow-texture").mesh;
    }

  private:
    bool bilinear_;
    int receiver_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(ShadowTexture, "shadow-texture",
                      "shadow texture: the casters' opacity from the light, projected onto the "
                      "receiver");

}  // namespace so
