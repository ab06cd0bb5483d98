// raytraced: ray-traced shadows and their denoisers (issue 53). Each frame, from every pixel's
// point of the camera pass (its G-buffer, read back: the pixels a GPU would shade), `spp` shadow
// rays to points on the light, traced by Embree on the CPU (shadow_rays.h: the work RT cores do on
// a GPU; an Owen-scrambled Sobol sequence per pixel advanced with the sequence's frame index); the
// estimate is uploaded as a texture and denoised by full-screen GLSL passes (fragment passes, so
// the counted frame counts their fragments, taps and bytes as every other family's). The
// denoisers are plug-ins (denoisers/denoiser.h: none, temporal, svgf, ffx, hitdist, rtg), picked
// by `denoiser=NAME`, each with its own parameters; the history they keep across a sequence's
// frames is denoisers/ray_frame.h's. An adaptive denoiser (rtg) decides before the trace how many
// of the `spp` rays each pixel traces (LightDenoiser::sampleCounts); the others trace spp
// everywhere. rays_traced counts the rays traced.
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/rays/shadow_rays.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/gl/time/temporal_state.h"

namespace so {
namespace {

class Raytraced final : public Technique {
  public:
    static constexpr const char* kFamily = kRayTracingFamily;
    // The named design is the denoiser's (its own provenance); the rays are the common hybrid
    // design, from a G-buffer to points on the light.
    static Provenance provenance() {
        return {
            "hybrid ray-traced shadows as engines ship them: shadow rays from the G-buffer to "
            "points on the light (Ray Tracing Gems, chapter 13, section 13.2), here traced by "
            "Embree on the CPU over the read-back G-buffer, light points from a per-pixel "
            "Owen-scrambled Sobol sequence",
            Fidelity::Own};
    }
    static ParamTable params() {
        const PluginAxis denoisers = denoiserAxis();
        ParamTable table = {
            {"spp",
             1,
             1,
             256,
             true,
             "shadow rays per pixel and frame, to points of a per-pixel scrambled Sobol sequence "
             "on the light (issue 53: 1, 2, 4 ...; FidelityFX's denoiser is built for 1); with "
             "denoiser=rtg the most a pixel traces (it adapts each pixel's count down to 1)",
             {},
             true},
            axisParam(denoisers, 0, denoiserDoc(denoisers))};
        for (ParamSpec& p : axisParams(denoisers)) table.push_back(std::move(p));
        return table;
    }
    explicit Raytraced(const ParamValues& v)
        : Technique(v), spp(v.integer("spp")), denoiser(createDenoiser(v)) {}
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override;
    bool buildsOverFrames() const override { return denoiser->keepsHistory(); }

    int spp;
    std::unique_ptr<const Denoiser> denoiser;

  private:
    // "none: the rays' estimate; temporal: ..." from the plug-ins' summaries.
    static std::string denoiserDoc(const PluginAxis& axis) {
        std::string doc;
        for (const AxisPlugin& p : axis.plugins)
            doc += (doc.empty() ? "" : "; ") + p.name + ": " + p.summary;
        return doc + " (docs/techniques.md#denoiser-plug-ins)";
    }
};

// The BVH, shared by the lights of one render.
struct SharedTracer : SetUpShared {
    explicit SharedTracer(const GpuScene& scene) : tracer(scene.scene(), scene.frame()) {}
    ShadowRayTracer tracer;
};

class RaytracedLight final : public LightTechnique {
  public:
    RaytracedLight(const Raytraced& technique, const LightSetup& setup);
    std::vector<std::string> passNames() const override;
    void renderLightPasses(PassClock& /*clock*/) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override {
        return frame_.memoryBytes() + denoiser_->memoryBytes();
    }

  private:
    void trace(PassClock& clock, const std::vector<uint8_t>& counts);

    const Raytraced& t_;
    const Light& light_;
    const CameraPass& camera_;
    int frameIndex_;
    std::shared_ptr<const SharedTracer> tracer_;
    // Without the caller's temporal state, a cold start: a store of its own, empty.
    RayHistoryStore coldStore_;
    RayFrame frame_;
    std::unique_ptr<LightDenoiser> denoiser_;
    GlProgram resolveProg_;
    uint64_t lastRays_ = 0, lastPixels_ = 0;
};

std::unique_ptr<LightTechnique> Raytraced::setUp(const LightSetup& setup) const {
    return std::make_unique<RaytracedLight>(*this, setup);
}

RaytracedLight::RaytracedLight(const Raytraced& technique, const LightSetup& setup)
    : t_(technique),
      light_(setup.light),
      camera_(setup.camera),
      frameIndex_(setup.frameIndex),
      frame_(setup.light, setup.scene, setup.camera, setup.frameIndex,
             setup.temporal ? setup.temporal->rayHistory(&technique) : coldStore_,
             technique.denoiser->result(), setup.temporal) {
    const std::string key = "raytraced.bvh";
    if (setup.shared && setup.shared->count(key))
        tracer_ = std::static_pointer_cast<const SharedTracer>(setup.shared->at(key));
    else {
        tracer_ = std::make_shared<const SharedTracer>(setup.scene);
        if (setup.shared) (*setup.shared)[key] = tracer_;
    }
    resolveProg_ = frame_.program("PASS_RESOLVE", "", {shaders::raytraced_glsl});
    denoiser_ = t_.denoiser->setUp(frame_);
}

std::vector<std::string> RaytracedLight::passNames() const {
    const std::vector<std::string> own = t_.denoiser->passNames();
    const auto beforeTrace = own.begin() + std::ptrdiff_t(t_.denoiser->passesBeforeTrace());
    std::vector<std::string> names(own.begin(), beforeTrace);
    names.push_back("trace");
    names.insert(names.end(), beforeTrace, own.end());
    names.push_back("resolve");
    return names;
}

// The G-buffer read back, the rays traced (`counts` of them per pixel, or spp where empty), their
// estimate uploaded.
void RaytracedLight::trace(PassClock& clock, const std::vector<uint8_t>& counts) {
    clock.begin("trace");
    const int W = frame_.width(), H = frame_.height();
    const size_t texels = size_t(W) * size_t(H);
    frame_.position.resize(4 * texels);
    frame_.normal.resize(4 * texels);
    const auto bytes = GLsizei(4 * texels * sizeof(float));
    glGetTextureImage(camera_.positionTexture(), 0, GL_RGBA, GL_FLOAT, bytes,
                      frame_.position.data());
    glGetTextureImage(camera_.normalTexture(), 0, GL_RGBA, GL_FLOAT, bytes, frame_.normal.data());
    ShadowRaySettings settings;
    settings.spp = t_.spp;
    settings.frameIndex = frameIndex_;
    settings.hitDistance = t_.denoiser->needsHitDistance();
    if (!counts.empty()) settings.samplesPerPixel = &counts;
    const ShadowRayFrame frame = tracer_->tracer.trace(
        {W, H, frame_.position.data(), frame_.normal.data()}, light_, settings);
    glTextureSubImage2D(frame_.raw.texture.get(), 0, 0, 0, W, H, GL_RG, GL_FLOAT,
                        frame.visibilityAndHit.data());
    lastRays_ = frame.raysTraced;
    lastPixels_ = frame.pixelsTraced;
    clock.addRays(frame.raysTraced);
    clock.end();
}

void RaytracedLight::renderVisibility(PassClock& clock) {
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    glDisable(GL_DEPTH_TEST);
    glBindTextureUnit(1, camera_.positionTexture());
    glBindTextureUnit(2, camera_.normalTexture());
    trace(clock, denoiser_->sampleCounts(clock, t_.spp));
    glBindTextureUnit(1, camera_.positionTexture());
    glBindTextureUnit(2, camera_.normalTexture());
    const GLuint result = denoiser_->denoise(clock);
    clock.begin("resolve");
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    glBindTextureUnit(0, result);
    glUseProgram(resolveProg_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    clock.end();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
}

RasterLightStats RaytracedLight::describe() const {
    RasterLightStats s;
    s.counts = {{"rays_traced", int64_t(lastRays_)}, {"pixels_traced", int64_t(lastPixels_)}};
    return s;
}

}  // namespace

SO_REGISTER_TECHNIQUE(Raytraced, "raytraced",
                      "shadow rays from the G-buffer traced by Embree (spp a frame), denoised: "
                      "none, temporal, svgf, ffx, hitdist or rtg");

}  // namespace so
