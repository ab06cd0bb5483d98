// accumulate: soft shadows as the average of many hard ones (the course's "many point lights,
// additive blending"): `samples` points on the area light, from an Owen-scrambled Sobol sequence
// as the oracle's are (uniform by area on rect and disk lights, uniform over a sphere light's
// surface), each a point light whose hard shadow a technique renders: `method=volume` stencil
// shadow volumes (volume-zfail, exact per sample), `method=map` a slope-biased shadow map of
// `resolution`. Each sample's V is weighted per pixel as the oracle weights its samples, by G =
// cos(receiver) cos(emitter) / r^2 (one-sided for rect and disk lights), and the result is sum(G v)
// / sum(G): the limit as the samples grow is the oracle's V, not an unweighted average. Lights that
// are not area lights are their own single sample. Every sample's passes run every frame: the cost
// grows with `samples`. Alpha-tested casters are what the inner technique makes of them: opaque
// with method=volume (the volumes are built from whole triangles), cut by their masks with
// method=map.
#include <deque>

#include "core/lights/light_kind.h"
#include "core/lights/make_light.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/lights/light_samples.h"
#include "raster_compare/gl/lights/raster_light_kind.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

class Accumulate;

class AccumulateLight final : public LightTechnique {
  public:
    AccumulateLight(const Accumulate& technique, const LightSetup& setup);
    std::vector<std::string> passNames() const override;
    void renderLightPasses(PassClock& clock) override {
        for (auto& s : samples_) s->renderLightPasses(clock);
    }
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override;

  private:
    const Light& light_;
    const CameraPass& camera_;
    std::deque<Light> points_;  // the samples' point lights (the inner objects refer to them)
    std::vector<glm::vec3> lsSamples_;
    std::vector<std::unique_ptr<LightTechnique>> samples_;
    LightTarget sampleTarget_;  // one sample's hard V, with the camera pass's depth and stencil
    GlTexture sums_;
    GlFramebuffer sumsFbo_;
    GlProgram weightProg_, resolveProg_;
};

class Accumulate final : public Technique {
  public:
    static constexpr const char* kFamily = "accumulation";
    static Provenance provenance() {
        return {
            "Heckbert and Herf, \"Simulating Soft Shadows with Graphics Hardware\", CMU-CS-97-104 "
            "(1997): a soft shadow as the average of hard shadows from points on the light",
            Fidelity::Own};
    }
    static ParamTable params() {
        return {{"samples", 64, 1, 1024, true, "points on the light, each a hard shadow", {}, true},
                methodParam("method", 1, {"map", "volume"},
                            "volume: stencil shadow volumes (volume-zfail: alpha-tested casters "
                            "opaque); map: slope-biased shadow maps (alpha-tested)"),
                {"resolution", 512, 16, 16384, true, "method=map: each map's side in texels"}};
    }
    explicit Accumulate(const ParamValues& v)
        : Technique(v),
          samples(v.integer("samples")),
          inner(v.integer("method") == 1
                    ? createTechnique("volume-zfail", {})
                    : createTechnique("slope-bias",
                                      {"resolution=" + std::to_string(v.integer("resolution"))})) {}
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override {
        return std::make_unique<AccumulateLight>(*this, setup);
    }
    int samples;
    std::unique_ptr<Technique> inner;
};

AccumulateLight::AccumulateLight(const Accumulate& technique, const LightSetup& setup)
    : light_(setup.light), camera_(setup.camera), sampleTarget_(setup.camera) {
    for (const glm::dvec3& p : lightSamplePoints(light_, technique.samples)) {
        points_.push_back(isAreaLight(light_) ? pointLightAt(light_, p) : light_);
        lsSamples_.push_back(glm::vec3(setup.scene.frame().lsFromWs(p)));
        samples_.push_back(technique.inner->setUp(
            {points_.back(), setup.scene, setup.camera, setup.lsReceivers, nullptr}));
    }
    sums_ = makeTexture(GL_TEXTURE_2D);
    glTextureStorage2D(sums_.get(), 1, GL_RG32F, camera_.width(), camera_.height());
    sumsFbo_ = makeFramebuffer();
    glNamedFramebufferTexture(sumsFbo_.get(), GL_COLOR_ATTACHMENT0, sums_.get(), 0);
    const LocalFrame& frame = setup.scene.frame();
    const std::string kind = rasterLightKind(light_.type).emitterDefine();
    weightProg_ = buildProgram("#define WEIGHT_PASS\n" + kind + camera_.texelBytesDefines() +
                                   sampleTarget_.texelBytesDefines(),
                               shaders::fullscreen_vert, {shaders::accumulate_glsl});
    const GLuint wp = weightProg_.get();
    setVec3(wp, "u_lsLightCenter", frame.lsFromWs(light_.wsPosition));
    if (isOneSided(light_)) setVec3(wp, "u_lsEmitNormal", light_.wsEmitNormal());
    for (const char* name : {"u_visibility", "u_position", "u_normal"})
        setInt(wp, name, name[2] == 'v' ? 0 : name[2] == 'p' ? 1 : 2);
    resolveProg_ =
        buildProgram("#define SUMS_TEXEL_BYTES " + std::to_string(texelBytes(sums_.get())) + "\n",
                     shaders::fullscreen_vert, {shaders::accumulate_glsl});
    setInt(resolveProg_.get(), "u_sums", 0);
}

std::vector<std::string> AccumulateLight::passNames() const {
    std::vector<std::string> names = samples_.front()->passNames();
    names.push_back("accumulate");
    return names;
}

// Per sample: its hard shadow into the sample target, then its weighted V added to the sums;
// finally V = sum(G v) / sum(G) into the light's target.
void AccumulateLight::renderVisibility(PassClock& clock) {
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(sumsFbo_.get(), GL_COLOR, 0, zero);
    for (size_t i = 0; i < samples_.size(); ++i) {
        sampleTarget_.bindAndClear();
        samples_[i]->renderVisibility(clock);
        clock.begin("accumulate");
        glBindFramebuffer(GL_FRAMEBUFFER, sumsFbo_.get());
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(weightProg_.get());
        glProgramUniform3f(weightProg_.get(), glGetUniformLocation(weightProg_.get(), "u_lsSample"),
                           lsSamples_[i].x, lsSamples_[i].y, lsSamples_[i].z);
        glBindTextureUnit(0, sampleTarget_.visibilityTexture());
        glBindTextureUnit(1, camera_.positionTexture());
        glBindTextureUnit(2, camera_.normalTexture());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        clock.end();
    }
    clock.begin("accumulate");
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    glDisable(GL_DEPTH_TEST);
    glUseProgram(resolveProg_.get());
    glBindTextureUnit(0, sums_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
    clock.end();
}

RasterLightStats AccumulateLight::describe() const {
    RasterLightStats s;
    s.counts = {{"samples", int64_t(samples_.size())}};
    return s;
}

uint64_t AccumulateLight::memoryBytes() const {
    uint64_t bytes = uint64_t(camera_.width()) * uint64_t(camera_.height()) * (4 + 4 + 8);
    for (const auto& s : samples_) bytes += s->memoryBytes();
    return bytes;
}

}  // namespace

SO_REGISTER_TECHNIQUE(Accumulate, "accumulate",
                      "many hard shadows from points on the light, G-weighted like the oracle's "
                      "samples");

}  // namespace so
