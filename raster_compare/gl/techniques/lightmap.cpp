// lightmap: static shadows baked once into a texture over the surfaces, filtered and looked up
// every frame (the course notes' last technique: "very used in games"). At set-up, per light, the
// static meshes get an atlas (their TEXCOORD_1, else charts of coplanar connected triangles,
// shelf-packed with `padding`) at `texels_per_unit`, and the raster path bakes V into it from a
// `bake_resolution` shadow map (area lights: `bake_samples` of them, G-weighted), growing each
// chart `dilate` texels into its padding; per frame one visibility pass reads the atlas with
// `filter`. The bake's time is `bake_ms`, apart from the frame's. A mesh marked dynamic casts no
// shadow here (docs/scene-format.md): a lightmap cannot shadow what moves.
#include "raster_compare/gl/lightmaps/lightmap.h"
#include "raster_compare/gl/shaders.h"

namespace so {
namespace {

class Lightmap final : public Technique {
  public:
    static constexpr const char* kFamily = "lightmap";
    static Provenance provenance() {
        return {
            "baked lightmaps over a UV atlas (TEXCOORD_1), as engines bake static shadows; the "
            "bake is a high-resolution shadow map of ours",
            Fidelity::Own};
    }
    static ParamTable params() {
        return {{"texels_per_unit",
                 32,
                 0.01,
                 4096,
                 false,
                 "atlas texels per world unit of surface, along each side (density)",
                 {},
                 true},
                {"padding", 2, 0, 64, true, "empty texels around each chart in the atlas"},
                methodParam("filter", 1, {"nearest", "bilinear", "bicubic"},
                            "the lookup: the texel holding the point, the four nearest texel "
                            "centres, or a cubic B-spline over the 4 x 4 nearest"),
                {"dilate", 2, 0, 64, true,
                 "texels each chart grows into its padding after the bake, against seams"},
                {"bake_resolution", 2048, 16, 16384, true,
                 "side of the shadow map the bake tests each texel against (cube maps: per face)"},
                {"bake_samples", 64, 1, 4096, true,
                 "area lights (with the penumbra effect): points on the light baked, each a hard "
                 "shadow, G-weighted"}};
    }
    explicit Lightmap(const ParamValues& v) : Technique(v) {
        settings_.atlas.texelsPerUnit = v.real("texels_per_unit");
        settings_.atlas.padding = v.integer("padding");
        settings_.bake.dilate = v.integer("dilate");
        settings_.bake.resolution = v.integer("bake_resolution");
        settings_.bake.samples = v.integer("bake_samples");
        settings_.glsl = shaders::lightmap_glsl;
        static const char* const kFilters[3] = {"FILTER_NEAREST", "FILTER_BILINEAR",
                                                "FILTER_BICUBIC"};
        settings_.defines = std::string("#define ") + kFilters[v.integer("filter")] + "\n";
    }
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override {
        return setUpLightmap(settings_, setup);
    }

  private:
    LightmapSettings settings_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Lightmap, "lightmap",
                      "static shadows baked into an atlas over the surfaces (TEXCOORD_1 or "
                      "coplanar charts) from a high-resolution shadow map, filtered at lookup; "
                      "dynamic meshes cast none");

}  // namespace so
