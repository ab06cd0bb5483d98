// ffx: AMD's FidelityFX Shadow Denoiser (MIT; GPUOpen-Effects/FidelityFX-Denoiser d7dfecb,
// ffx-shadows-dnsr; the FidelityFX SDK 1.1.4's passes), its kernels as fragment passes
// (ffx.glsl, which cites each constant): tile classification over 8 x 8 groups (a group whose
// 24 x 24 region of rays all agree, or with no receiver, skips the rest), the temporal pass
// (Welford moments with their count, the history clamped to a 17 x 17 neighbourhood's mean +- half
// a standard deviation, the count damped by the history's distance from that mean, the new frame
// weighing 1 down to 0.05 as the count reaches 8), then three edge-avoiding 3 x 3 passes at steps
// 1, 2, 4, the first pass's output the next frame's history and the last one's contrast remapped
// (mean^max(1.2 - variance, 1)).
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/shaders.h"

namespace so {
namespace {

class FfxLight final : public LightDenoiser {
  public:
    FfxLight(RayFrame& frame, double depthSimilaritySigma)
        : frame_(frame),
          classify_(frame.program("PASS_CLASSIFY", "", {shaders::ffx_glsl})),
          temporal_(
              frame.program("PASS_TEMPORAL", "", {shaders::reprojection_glsl, shaders::ffx_glsl})),
          filter_(frame.program("PASS_FILTER", "", {shaders::ffx_glsl})),
          temporalFbo_(makeFramebuffer()) {
        // The temporal pass writes the moments (accum) and V with its variance (filterA) at once.
        const GLuint fbo = temporalFbo_.get();
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, frame.accum.texture.get(), 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, frame.filterA.texture.get(), 0);
        const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(fbo, 2, both);
        const glm::dmat4& clipFromLocal = frame.camera().clipFromLocal();
        setMat4(temporal_.get(), "u_clipFromLocal", clipFromLocal);
        setMat4(filter_.get(), "u_clipFromLocal", clipFromLocal);
        setFloat(filter_.get(), "u_lsDepthSimilarity",
                 frame.scene().frame().lsLength(depthSimilaritySigma));
    }
    GLuint denoise(PassClock& clock) override {
        classify(clock);
        clock.begin("temporal");
        frame_.bindHistory(temporal_);
        glBindTextureUnit(5, frame_.tiles.texture.get());  // read by the filter passes too
        glBindFramebuffer(GL_FRAMEBUFFER, temporalFbo_.get());
        glUseProgram(temporal_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        clock.end();
        // FFX SDK 1.1.4, ffx_denoiser.cpp 612-622: filterA -> filterB (the history) -> filterA ->
        // filterB.
        filter(clock, frame_.filterA, frame_.filterB, 0);
        frame_.keepHistory(frame_.filterB.texture.get());
        filter(clock, frame_.filterB, frame_.filterA, 1);
        filter(clock, frame_.filterA, frame_.filterB, 2);
        return frame_.filterB.texture.get();
    }

  private:
    // Which 8 x 8 groups skip the denoiser, drawn one fragment per group into frame.tiles (sized
    // for 8 x 4 tiles: the groups use its lower half).
    void classify(PassClock& clock) {
        clock.begin("classify");
        glViewport(0, 0, (frame_.width() + 7) / 8, (frame_.height() + 7) / 8);
        glBindTextureUnit(0, frame_.raw.texture.get());
        frame_.draw(frame_.tiles, classify_);
        glViewport(0, 0, frame_.width(), frame_.height());
        clock.end();
    }
    // Filter pass `pass` (0, 1, 2: steps 1, 2, 4).
    void filter(PassClock& clock, const ScreenTarget& in, const ScreenTarget& out, int pass) {
        clock.begin("filter");
        setInt(filter_.get(), "u_step", 1 << pass);
        setInt(filter_.get(), "u_last", pass == 2 ? 1 : 0);
        glBindTextureUnit(0, in.texture.get());
        frame_.draw(out, filter_);
        clock.end();
    }

    RayFrame& frame_;
    GlProgram classify_, temporal_, filter_;
    GlFramebuffer temporalFbo_;
};

class Ffx final : public Denoiser {
  public:
    static constexpr int kNumber = 3;
    static ParamTable params() {
        return {{"depth_similarity_sigma", 1.0, 1e-3, 1000, false,
                 "the filters' depth stop exp(-abs(z - z') / sigma) on view depth, in scene units "
                 "(FidelityFX SDK 1.1.4, ffx_denoiser.h:126 \"defaults to 1.0f\"; its "
                 "hybridshadows sample sets 1, hybridshadowsrendermodule.cpp:683)"}};
    }
    static Provenance provenance() {
        return {
            "AMD FidelityFX Denoiser v1.2 (GPUOpen-Effects/FidelityFX-Denoiser d7dfecb), "
            "ffx-shadows-dnsr/ffx_denoiser_shadows_tileclassification.h and "
            "ffx_denoiser_shadows_filter.h; FidelityFX SDK 1.1.4 (c6efa6b), "
            "ffx_denoiser_shadows_filter.h (DenoiserShadowsFilterPass0-2)",
            Fidelity::Variant,
            {"reprojects by the camera's motion only (the raster path has no per-mesh motion "
             "vectors), where FFX reads each 2 x 2 quad's closest velocity: a moving mesh's "
             "own pixels lose their history",
             "spp > 1: a pixel's V is its rays' fraction where FFX's mask holds one ray's bit "
             "(the neighbourhood's second moment kept apart from its mean; a region uniform "
             "only where every V is 0 or every V is 1)",
             "fragment passes in 32-bit floats where FFX packs rays into 8 x 4 bit masks and "
             "its filters' V, variance and normals into 16-bit floats in group-shared "
             "memory"}};
    }
    explicit Ffx(const ParamValues& v) : depthSimilaritySigma(v.real("depth_similarity_sigma")) {}
    std::vector<std::string> passNames() const override {
        return {"classify", "temporal", "filter"};
    }
    RayTarget result() const override { return RayTarget::Filter; }
    std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const override {
        return std::make_unique<FfxLight>(frame, depthSimilaritySigma);
    }

    double depthSimilaritySigma;
};

}  // namespace

SO_REGISTER_DENOISER(Ffx, "ffx",
                     "AMD FidelityFX Shadow Denoiser: tile classification, temporal moments "
                     "clamped to the neighbourhood, three edge-avoiding passes");

}  // namespace so
