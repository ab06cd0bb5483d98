// blur: the course's post-processing soft shadow. A hard shadow (a slope-biased shadow map of
// `resolution`) is rendered into the screen, then blurred there by a separable Gaussian of
// `radius` pixels (sigma = radius / 2). With `bilateral=on` a tap counts only where the camera
// sees the same kind of surface: its normal within about 25 degrees and its distance within 5%
// of the pixel's, so the blur does not run across silhouettes. The penumbra's width is the
// radius everywhere, whatever the distance from occluder to receiver: what the metrics measure.
// radius=0 is the hard shadow itself (tested).
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

class Blur;

class BlurLight final : public LightTechnique {
  public:
    BlurLight(const Blur& technique, const LightSetup& setup);
    std::vector<std::string> passNames() const override {
        std::vector<std::string> names = hard_->passNames();
        names.push_back("blur");
        return names;
    }
    void renderLightPasses(PassClock& clock) override { hard_->renderLightPasses(clock); }
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override { return hard_->describe(); }
    bool probeDepth(bool on) override {
        hardTarget_.setProbing(on);
        return hard_->probeDepth(on);
    }
    // The hard shadow's comparison, as its own target holds it, with its V before the blur.
    std::optional<DepthComparison> readDepthComparison(const LightTarget&) const override {
        std::optional<DepthComparison> c = hard_->readDepthComparison(hardTarget_);
        if (c) c->unfilteredVisibility = hardTarget_.readVisibility();
        return c;
    }
    uint64_t memoryBytes() const override {
        return hard_->memoryBytes() + uint64_t(camera_.width()) * uint64_t(camera_.height()) * 12;
    }

  private:
    const CameraPass& camera_;
    std::unique_ptr<LightTechnique> hard_;
    // The hard V (and, where the frame wants it, the depth probe), with the camera pass's depth
    // and stencil.
    LightTarget hardTarget_;
    GlTexture across_;  // blurred along x
    GlFramebuffer acrossFbo_;
    GlProgram blurProg_;
};

class Blur final : public Technique {
  public:
    static constexpr const char* kFamily = "screen-space blur";
    static Provenance provenance() {
        return {
            "a hard shadow map blurred in screen space (the post-process soft shadow of the shadow "
            "course notes the seeds follow)",
            Fidelity::Own};
    }
    static ParamTable params() {
        return {
            {"radius", 4, 0, 64, true, "Gaussian radius in pixels (sigma = radius / 2)", {}, true},
            methodParam("bilateral", 0, {"off", "on"},
                        "on: only taps on a similar surface (normal and distance) count"),
            {"resolution", 2048, 16, 16384, true, "the hard shadow map's side in texels"}};
    }
    explicit Blur(const ParamValues& v)
        : Technique(v),
          radius(v.integer("radius")),
          bilateral(v.integer("bilateral") == 1),
          hard(createTechnique("slope-bias",
                               {"resolution=" + std::to_string(v.integer("resolution"))})) {}
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override {
        return std::make_unique<BlurLight>(*this, setup);
    }
    int radius;
    bool bilateral;
    std::unique_ptr<Technique> hard;
};

BlurLight::BlurLight(const Blur& technique, const LightSetup& setup)
    : camera_(setup.camera),
      hard_(technique.hard->setUp(setup)),
      hardTarget_(setup.camera, setup.depthProbe) {
    across_ = makeTexture(GL_TEXTURE_2D);
    glTextureStorage2D(across_.get(), 1, GL_R32F, camera_.width(), camera_.height());
    acrossFbo_ = makeFramebuffer();
    glNamedFramebufferTexture(acrossFbo_.get(), GL_COLOR_ATTACHMENT0, across_.get(), 0);
    blurProg_ = buildProgram(std::string(technique.bilateral ? "#define BILATERAL\n" : "") +
                                 camera_.texelBytesDefines() + hardTarget_.texelBytesDefines(),
                             shaders::fullscreen_vert, {shaders::blur_glsl});
    const GLuint p = blurProg_.get();
    setInt(p, "u_radius", technique.radius);
    setInt(p, "u_source", 0);
    setInt(p, "u_position", 1);
    setInt(p, "u_normal", 2);
    setVec3(p, "u_lsEye", camera_.lsEye());
}

// The hard shadow into hardV_, blurred across into across_, then down into the light's target.
void BlurLight::renderVisibility(PassClock& clock) {
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    hardTarget_.bindAndClear();
    hard_->renderVisibility(clock);
    clock.begin("blur");
    glDisable(GL_DEPTH_TEST);
    glUseProgram(blurProg_.get());
    const GLint step = glGetUniformLocation(blurProg_.get(), "u_step");
    glBindTextureUnit(1, camera_.positionTexture());
    glBindTextureUnit(2, camera_.normalTexture());
    glBindFramebuffer(GL_FRAMEBUFFER, acrossFbo_.get());
    glBindTextureUnit(0, hardTarget_.visibilityTexture());
    glProgramUniform2i(blurProg_.get(), step, 1, 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // aliasing: none for a blur
    glBindTextureUnit(0, across_.get());
    glProgramUniform2i(blurProg_.get(), step, 0, 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
    clock.end();
}

}  // namespace

SO_REGISTER_TECHNIQUE(Blur, "blur",
                      "a hard shadow map's shadow blurred in screen space (Gaussian, optionally "
                      "bilateral)");

}  // namespace so
