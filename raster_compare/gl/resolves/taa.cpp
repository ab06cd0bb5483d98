// resolve=taa: the frame resolved as Bevy resolves it, by a TAA of the lit image (taa.glsl), with
// its sub-pixel camera jitter; each light's V recovered from the resolved shadowed and unshadowed
// images. Bevy 0.19.1 (bevyengine/bevy b56fc29d): crates/bevy_anti_alias/src/taa/taa.wgsl (the
// resolve, unchanged since 0.14.0) and taa/mod.rs:366-378 (the jitter). Godot 4.6's TAA differs
// in its constants (docs/techniques.md#resolve lists them): a fixed blend of 0.0625, an RGB
// variance box that shrinks with motion, 16 Halton jitters.
#include <array>

#include "core/lights/light_kind.h"
#include "core/scene.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/resolves/resolve.h"
#include "raster_compare/gl/resolves/resolve_frame.h"
#include "raster_compare/gl/shaders.h"

namespace so {
namespace {

// Bevy 0.19.1's jitter, taa/mod.rs:366-376: Halton(2, 3) - 0.5 from index 0, 8 entries, in
// pixels, indexed by frame_count % 8 (mod.rs:378), y down the screen.
constexpr std::array<std::array<double, 2>, 8> kBevyJitter = {{{0.0, 0.0},
                                                               {0.0, -1.0 / 6.0},
                                                               {-0.25, 1.0 / 6.0},
                                                               {0.25, -7.0 / 18.0},
                                                               {-0.375, -1.0 / 18.0},
                                                               {0.125, 5.0 / 18.0},
                                                               {-0.125, -5.0 / 18.0},
                                                               {0.375, 1.0 / 18.0}}};

class Taa final : public Resolve {
  public:
    static constexpr int kNumber = 1;
    static Provenance provenance() {
        return {
            "Bevy 0.19.1 TAA (bevyengine/bevy b56fc29d): "
            "crates/bevy_anti_alias/src/taa/taa.wgsl:77-200 (the resolve) and "
            "taa/mod.rs:366-378 (the jitter), on the lit image of white Lambert surfaces",
            Fidelity::Variant,
            {"two grey lit images per light (shadowed V E and unshadowed E, E = max(0, n.l) "
             "without the light's falloff), each resolved as a view target, V recovered as "
             "their ratio, where Bevy resolves one colour image of every light",
             "motion vectors computed per pixel from the exact camera and mesh motion, where "
             "Bevy's prepass rasterises them (the same values for rigid motion)",
             "the history in RGBA32F, where Bevy keeps Rgba16Float (HDR) or the view's "
             "format"}};
    }
    static ParamTable params() { return {}; }
    explicit Taa(const ParamValues&) {}
    std::vector<std::string> passNames() const override { return {"taa"}; }
    glm::dvec2 jitterPixels(int frameIndex) const override {
        const auto& o = kBevyJitter[size_t(frameIndex) % kBevyJitter.size()];
        // Bevy adds offset * (2, -2) / size to the projection: the image moves by -offset
        // pixels, y down; the camera pass's jitter is the image's move with y up.
        return {-o[0], o[1]};
    }
    std::unique_ptr<LightResolve> setUp(const ResolveSetup& setup) const override;
};

// Taa's pass: the frame's inputs, the light, and the history bilinear on unit 5.
class TaaLight final : public OnePassResolve {
  public:
    explicit TaaLight(const ResolveSetup& setup)
        : OnePassResolve(setup, "taa", "", {shaders::taa_glsl}), linear_(makeSampler()) {
        const GLuint p = program();
        setInt(p, "u_prevHistoryLinear", 5);
        setMat4(p, "u_unjitteredClipFromLocal", setup.camera.unjitteredClipFromLocal());
        setVec3(p, "u_lsEye", setup.camera.lsEye());
        const bool directional = isDirectional(setup.light);
        setInt(p, "u_lightDirectional", directional ? 1 : 0);
        setVec3(p, "u_lsLight",
                directional ? -setup.light.wsDirection
                            : setup.scene.frame().lsFromWs(setup.light.wsPosition));
        glSamplerParameteri(linear_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glSamplerParameteri(linear_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glSamplerParameteri(linear_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(linear_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }

  private:
    void bindOwn() override {
        glBindTextureUnit(5, frame().previousHistoryTexture());
        glBindSampler(5, linear_.get());
    }
    void unbindOwn() override { glBindSampler(5, 0); }

    GlSampler linear_;
};

std::unique_ptr<LightResolve> Taa::setUp(const ResolveSetup& setup) const {
    return std::make_unique<TaaLight>(setup);
}

}  // namespace

SO_REGISTER_RESOLVE(Taa, "taa",
                    "Bevy's TAA of the lit image (sub-pixel camera jitter, 3x3 YCoCg variance "
                    "clip, blend between 0.015 and 0.1), V recovered from the resolved images");

}  // namespace so
