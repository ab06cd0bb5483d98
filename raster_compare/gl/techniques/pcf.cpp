// pcf: percentage-closer filtering: the binary depth test averaged over a kernel x kernel grid of
// texels around the lookup (the tests are averaged, never the depths), or over a 16-tap Poisson
// disk of radius kernel / 2 + 1/2, each tap compared at the depth its bias gives (`bias`, biases/;
// by default the slope-scaled bias of slope-bias times (1 + kernel / 2): the outer taps see the
// receiver's plane that many texels away, BIAS_SPREAD). With
// temporal=on (docs/techniques.md#temporal) the same number of taps lie on a Vogel disk turned
// per pixel and frame by interleaved gradient noise, over the area of the pattern it replaces
// (the grid's square: radius (2 (kernel / 2) + 1) / sqrt(pi) texels; the Poisson disk's radius),
// and a ShadowHistory resolves them over frames.
// pattern=three|bevy|godot are the tap patterns those engines ship (issue 63), each tap the
// sampler's 2x2 compare (GL_LINEAR, as hw-pcf), nothing accumulated: their constants and sources
// are in enginePatternDefines below and in techniques.md's parameter table.
#include <cmath>
#include <numbers>

#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/time/temporal_taps.h"

namespace so {
namespace {

enum class Pattern { Grid, Poisson, Three, Bevy, Godot };

// Where each value of `pattern` comes from (ParamSpec::provenances, parallel to the names).
std::vector<Provenance> patternProvenances() {
    return {
        {"Reeves, Salesin and Cook, SIGGRAPH 1987 (percentage-closer filtering), on a regular grid",
         Fidelity::Own},
        {"the 16-point Poisson disk of opengl-tutorial.org, tutorial 16 (shadow mapping)",
         Fidelity::Own},
        {"three.js r187 (npm three 0.187.0), src/renderers/shaders/ShaderChunk/"
         "shadowmap_pars_fragment.glsl.js getShadow 150-191 and getPointShadow 356-427 "
         "(PCFShadowMap; PR 32381); WebGPU src/nodes/lighting/ShadowFilterNode.js "
         "PCFShadowFilter 72-102",
         Fidelity::Variant,
         {"radius kernel / 2 texels, whole numbers only (three.js: shadow.radius, any real, "
          "default 1 = kernel 3, src/lights/LightShadow.js:87)",
          "the reference depth is our `bias` axis's (default slope bias), not shadow.bias "
          "(default 0) added in NDC",
          "point lights: the disk lies on the cube face's axes at the major-axis depth, where "
          "three.js builds a tangent frame and recomputes each tap's depth"}},
        {"Bevy main 4805ca7, crates/bevy_pbr/src/render/shadow_sampling.wesl "
         "sample_shadow_map_jimenez_fourteen 173-205, random_rotation_matrix 152-159, "
         "calculate_uv_offset_scale_jimenez_fourteen 165-171; utils.wesl 45-48, 61-68 "
         "(ShadowFilteringMethod::Temporal, Jimenez 2014)",
         Fidelity::Variant,
         {"gl_FragCoord's origin is the bottom-left pixel (WGSL's the top-left): the same "
          "noise, mirrored vertically",
          "the reference depth is our `bias` axis's, not Bevy's depth and normal biases",
          "point lights: the spiral on the cube face's axes at the major-axis depth, scaled "
          "0.0015 / texel angle (Bevy: POINT_SHADOW_SCALE 0.003 x 0.5 of the distance on an "
          "orthonormal basis)",
          "its TAA (Bevy documents Temporal for use with TemporalAntiAliasing) only with "
          "temporal=on (resolve=taa, Bevy 0.19.1's, issue 64); without, the noise as it "
          "falls"}},
        {"Godot 4 master, servers/rendering/renderer_rd/shaders/scene_forward_lights_inc.glsl "
         "sample_directional_pcf_shadow, sample_pcf_shadow; renderer_scene_render_rd.cpp "
         "directional_soft_shadow_filter_set_quality (SOFT_LOW, the project default 2: 4 taps, "
         "radius 2)",
         Fidelity::Variant,
         {"gl_FragCoord's origin is the bottom-left pixel (Vulkan's the top-left): the same "
          "noise, mirrored vertically",
          "the reference depth is our `bias` axis's, not Godot's depth and normal biases",
          "one cascade's radius: Godot scales later cascades by their size ratio (blur_factor)",
          "point lights: the disk on a cube face, where Godot samples a dual paraboloid",
          "its frame term and TAA only with temporal=on,resolve=taa, and that TAA is Bevy's "
          "constants (Godot 4.6's differ: docs/techniques.md#resolve); no FSR"}},
    };
}

// The engines' constants (cited in patternProvenances): TAPS, the offsets' scale in texels
// (PATTERN_TEXELS, or a per-light expression in the shader for Bevy), and whether the
// rotation reads the frame index.
std::string enginePatternDefines(Pattern p, int radius) {
    std::string d = "#define PATTERN_ENGINE\n";
    switch (p) {
        case Pattern::Three:  // 5 Vogel taps, radius shadow.radius texels, no frame term
            return d + "#define PATTERN_THREE\n#define PCF_TAPS 5\n" +
                   glslDefine("PATTERN_TEXELS", radius);
        case Pattern::Bevy:  // Jimenez 2014's 8-tap spiral, frame % 64
            return d + "#define PATTERN_BEVY\n#define PCF_TAPS 8\n";
        case Pattern::Godot:  // SOFT_LOW: 4 Vogel taps, shadow_blur 1 x quality radius 2
            return d + "#define PATTERN_GODOT\n#define PCF_TAPS 4\n" +
                   glslDefine("PATTERN_TEXELS", 2.0);
        default:
            return "";
    }
}

class Pcf final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        ParamSpec pattern = methodParam(
            "pattern", 0, {"grid", "poisson", "three", "bevy", "godot"},
            "grid: kernel x kernel taps; poisson: a 16-tap Poisson disk; three: three.js r182+ "
            "PCFShadowMap (5 Vogel taps of radius kernel / 2 texels turned per pixel, no frame "
            "term); bevy: Bevy's Temporal filter (8 spiral taps, turned per pixel and frame "
            "% 64); godot: Godot 4's soft shadows at their default quality (4 Vogel taps of "
            "radius 2 texels, turned per pixel, and per frame % 16 only under its TAA: "
            "temporal=on,resolve=taa); the engines' taps are hardware 2x2 compares; bevy and "
            "godot leave the noise to a TAA (temporal=on resolves them, `resolve`)");
        pattern.provenances = patternProvenances();
        ParamTable own = {
            {"kernel", 3, 1, 15, true, "grid side in texels, odd", {1, 3, 5, 7, 9, 11, 13, 15}},
            pattern};
        own = withBiasAxis(std::move(own), "slope");
        for (ParamSpec s : TemporalTaps::params()) {
            // three.js's taps have no frame term and nothing resolves them over frames; Bevy's
            // and Godot's turn as the engines turn them, and temporal=on resolves them
            // (`resolve`) without turning them again.
            if (s.name == "temporal") s.needs = "pattern=grid|poisson|bevy|godot";
            own.push_back(s);
        }
        return shadowMapParams(own);
    }
    static Provenance provenance() {
        return {"Reeves, Salesin and Cook, SIGGRAPH 1987 (percentage-closer filtering)",
                Fidelity::Variant,
                {"a fixed pattern of taps (`pattern`) where the paper samples the filter region "
                 "stochastically"}};
    }
    explicit Pcf(const ParamValues& v)
        : ShadowMapTechnique(v),
          radius_(v.integer("kernel") / 2),
          pattern_(Pattern(v.integer("pattern"))),
          temporal_(v) {}
    MapStorage storage() const override {
        return engine() ? MapStorage::DepthHardwareCompare : MapStorage::Depth;
    }
    const char* glsl() const override { return shaders::pcf_glsl; }
    std::string shaderDefines() const override {
        const bool poisson = pattern_ == Pattern::Poisson;
        std::string d = std::string(poisson ? "#define POISSON\n" : "") + "#define PCF_RADIUS " +
                        std::to_string(radius_) +
                        "\n#define BIAS_SPREAD (1.0 + float(PCF_RADIUS))\n";
        if (engine()) {
            // Godot turns its pattern per frame only under its TAA (taa_frame_count is 0
            // without): with resolve=taa.
            const Resolve* r = temporal_.resolve();
            if (pattern_ == Pattern::Godot && r && r->name() == "taa") d += "#define GODOT_TAA\n";
            return d + enginePatternDefines(pattern_, radius_);
        }
        d += temporal_.defines();
        if (!temporal_.on) return d;  // off: the defines it always had, the same shader
        const int side = 2 * radius_ + 1;
        const int taps = poisson ? 16 : side * side;
        const double diskTexels = poisson ? radius_ + 0.5 : side / std::sqrt(std::numbers::pi);
        return d + "#define PCF_TAPS " + std::to_string(taps) + "\n" +
               glslDefine("PCF_DISK_TEXELS", diskTexels);
    }
    const Resolve* resolve() const override { return temporal_.resolve(); }

  private:
    bool engine() const { return pattern_ != Pattern::Grid && pattern_ != Pattern::Poisson; }

    int radius_;  // texels from the centre tap
    Pattern pattern_;
    TemporalTaps temporal_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(
    Pcf, "pcf",
    "percentage-closer filtering: the depth test averaged over a kernel x kernel "
    "grid, 16 Poisson-disk taps or an engine's pattern (three, bevy, godot), each at its bias "
    "(by default the slope bias times (1 + kernel / 2))");

}  // namespace so
