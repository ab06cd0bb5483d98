// adaptive: an adaptive (virtual) shadow map (Fernando et al., "Adaptive Shadow Maps", 2001; the
// paged virtual shadow maps of current engines). A large virtual map, a mip chain of pages
// (virtual_shadow_map.h), of which only the pages the camera's pixels need are rendered, into a
// physical pool of fixed size. Per frame and light:
//   mark: the scene from the camera (depth prepass, then a pass that counts each visible lit pixel
//     into the page its footprint needs: the coarsest level whose texel keeps the predicted
//     aliasing at or below 1 / density), and the counts read back to the CPU;
//   pages: pool slots allocated on the CPU (allocatePages: greedily, a page after its parent, to
//     the pixels served the most levels coarser than they need), the page table uploaded, and each
//     allocated page rendered with the light's projection cropped to it, drawing only the meshes
//     whose light-space bounds overlap it;
//   refine (refine=1, only when the pool cannot hold every page asked for): the pages pass took
//     half of the pool; a second mark pass asks only for the pixels near a shadow edge in those
//     pages (Fernando et al.'s edge refinement), and the rest of the pool goes to their pages;
//   visibility: the finest resident page at or coarser than the needed level, a slope-scaled bias
//     in that level's texels (slope-bias's parameters), linear depths compared.
// Directional lights (orthographic, fitted as fitLightCamera fits a plain map) and spot lights
// (perspective, cropped in clip space). Point and area lights fall back to a plain slope-bias cube
// map of the pool's memory (counts: cube_fallback = 1). The passes live in
// virtual_shadow_map_light.h, which smrt's map=adaptive shares.
#include <utility>

#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/shadow_maps/virtual_shadow_map_light.h"

namespace so {
namespace {

class Adaptive final : public Technique {
  public:
    // Its own family: the registry test holds every "shadow map" technique to be a
    // ShadowMapTechnique, whose single-map setUp this does not share.
    static constexpr const char* kFamily = "virtual shadow map";
    static Provenance provenance() {
        return {
            "Fernando, Fernandez, Bala and Greenberg, \"Adaptive Shadow Maps\", SIGGRAPH 2001, "
            "section 4 (a hierarchy of pages refined where the camera needs them)",
            Fidelity::Variant,
            {"pages are asked for by a GPU mark pass whose counts are read back each frame, not by "
             "the paper's software traversal of the camera image",
             "a fixed physical pool allocated greedily every frame: no page cache across frames, "
             "so every resident page is re-rendered each frame",
             "at most one edge refinement pass (refine=1), where the paper refines until the error "
             "bound is met",
             "the lookup takes the finest resident page with a slope-scaled bias in that level's "
             "texels (slope-bias's parameters)",
             "point and area lights fall back to a plain cube map (the paper is for spot and "
             "directional projections only)"}};
    }
    static ParamTable params();
    explicit Adaptive(const ParamValues& v)
        : Technique(v), map_(v, "adaptive"), bias_(v), fit_(v.integer("fit") == 1) {}
    bool needsReceiverBounds() const override { return fit_; }
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override;

  private:
    VirtualMapSettings map_;
    SlopeBias bias_;
    bool fit_;
};

ParamTable Adaptive::params() {
    ParamTable p = VirtualMapSettings::params();
    p.push_back(fitParam());
    for (ParamSpec& s : SlopeBias::params()) p.push_back(std::move(s));
    return p;
}

std::unique_ptr<LightTechnique> Adaptive::setUp(const LightSetup& setup) const {
    VirtualVisibility visibility;
    visibility.frag = shaders::adaptive_visibility_frag;
    // Point and area lights: a slope-bias cube map of the pool's memory.
    const CubeFallback slopeBias = [this](int resolution) {
        return createTechnique(
            "slope-bias",
            {settingText("resolution", resolution), "depth_format=32",
             settingText("slope_factor", bias_.factor), settingText("min", bias_.minTexels),
             settingText("max", bias_.maxTexels)});
    };
    return setUpVirtualShadowMap(map_, bias_, std::move(visibility), setup, slopeBias, false);
}

}  // namespace

SO_REGISTER_TECHNIQUE(Adaptive, "adaptive",
                      "virtual shadow map: pages at the texel density each pixel needs, in a pool");

}  // namespace so
