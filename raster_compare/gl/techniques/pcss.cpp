// pcss: percentage-closer soft shadows (Fernando, "Percentage-Closer Soft Shadows", 2005). Three
// steps per pixel on a plain depth map rendered from the light's centre: a blocker search over the
// region of the map the light's cone through the receiver can cover, the penumbra's width from
// the average blocker depth by similar triangles, w = light size (d_receiver - d_blocker) /
// d_blocker, then PCF over that width. Both are bounded in the light's terms, not the map's:
// blockers are looked for, and taken, no nearer the light than d_receiver / (1 + `penumbra_max`),
// so the penumbra's half-width at the receiver is at most `penumbra_max` half-widths of the light
// at any resolution and scene size (directional lights: down to the scene's top); texel caps made
// the result depend on both (issues 29 and 42, docs/techniques.md "At real-scene scale"). Each tap
// is tested against the receiver's plane where the tap's ray meets it (Isidoro's receiver-plane
// depth) less its bias (`bias`, biases/; by default the slope bias of one texel), so the bias does
// not grow with the filter's width (a bias spread over the filter lit walls in an umbra). Taps on a
// golden-angle spiral
// (`blocker_samples`, `filter_samples`), the same for every pixel (no noise) or turned per pixel
// (`pattern`). The light's size is the side of a square of its area (rect: sqrt(|u x v|), disk and
// sphere: r sqrt(pi)), or `light_size` world units when >= 0 (for directional lights: the tangent
// of its angular diameter); point, spot and directional lights have none, which makes pcss a hard
// test. Assumes what Fernando's derivation does: blockers, receiver and light in parallel planes.
// With temporal=on (docs/techniques.md#temporal) both spirals turn per pixel and per frame
// (interleaved gradient noise offset by the frame index), and a ShadowHistory resolves them.
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/time/temporal_taps.h"

namespace so {
namespace {

class Pcss final : public ShadowMapTechnique {
  public:
    static Provenance provenance() {
        return {
            "Fernando, \"Percentage-Closer Soft Shadows\", SIGGRAPH 2005 sketch and NVIDIA "
            "whitepaper (blocker search, similar-triangle penumbra estimate, variable-width PCF)",
            Fidelity::Variant,
            {"blocker search and penumbra bounded by penumbra_max half-widths of the light (issues "
             "29 and 42), not by texel counts",
             "taps on a golden-angle spiral (optionally turned per pixel) where the whitepaper "
             "uses a fixed Poisson disk",
             "each tap compared against the receiver's plane along the tap's ray, less the depth "
             "bias axis's bias",
             "the light size is the side of a square of the light's area, or light_size"}};
    }
    static ParamTable params() {
        ParamTable own = {
            {"light_size", -1, -1, 1e6, false,
             "light width in world units (directional: tan of its angular size); -1: the scene "
             "light's (side of a square of its area)"},
            {"blocker_samples", 16, 1, 256, true, "taps of the blocker search"},
            {"filter_samples", 32, 1, 256, true, "taps of the variable PCF", {}, true},
            methodParam("pattern", 0, {"spiral", "rotated"},
                        "taps: spiral, one golden-angle spiral for every pixel (smooth; may band "
                        "at few taps); rotated, the spiral turned per pixel by interleaved "
                        "gradient noise (banding traded for noise)"),
            {"penumbra_max", 2, 0, 1000, false,
             "largest penumbra half-width at the receiver, in half-widths of the light: blockers "
             "count no nearer the light than d_receiver / (1 + penumbra_max); directional lights "
             "ignore it"}};
        own = withBiasAxis(std::move(own), "slope");
        for (const ParamSpec& s : TemporalTaps::params()) own.push_back(s);
        return shadowMapParams(own);
    }
    explicit Pcss(const ParamValues& v)
        : ShadowMapTechnique(v),
          lightSize_(v.real("light_size")),
          blockerSamples_(v.integer("blocker_samples")),
          filterSamples_(v.integer("filter_samples")),
          rotated_(v.integer("pattern") == 1),
          penumbraMax_(v.real("penumbra_max")),
          temporal_(v) {}
    const char* glsl() const override { return shaders::pcss_glsl; }
    std::string shaderDefines() const override {
        return "#define BLOCKER_SAMPLES " + std::to_string(blockerSamples_) +
               "\n#define FILTER_SAMPLES " + std::to_string(filterSamples_) + "\n" +
               glslDefine("PENUMBRA_MAX", penumbraMax_) +
               (rotated_ ? "#define PATTERN_ROTATED\n" : "") + temporal_.defines();
    }
    const Resolve* resolve() const override { return temporal_.resolve(); }
    void setLightUniforms(GLuint program, const Light& light,
                          const LocalFrame& frame) const override {
        const double size = lightSize_ >= 0.0 ? lightSize_ : lightWidth(light);
        // Directional: a tangent, no length.
        setFloat(program, "u_lightSize", isDirectional(light) ? size : frame.lsLength(size));
    }

  private:
    double lightSize_;
    int blockerSamples_, filterSamples_;
    bool rotated_;
    double penumbraMax_;
    TemporalTaps temporal_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Pcss, "pcss",
                      "percentage-closer soft shadows: blocker search, penumbra width from the "
                      "light's size, variable PCF");

}  // namespace so
