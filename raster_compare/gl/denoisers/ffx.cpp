// ffx: the design of AMD's FidelityFX Shadow Denoiser (MIT; GPUOpen-Effects/FidelityFX-Denoiser,
// ffx-shadows-dnsr; written here from its description, for one ray a pixel): tile classification
// (8 x 4 tiles, its ray masks' size: a tile whose rays and its neighbour tiles' rays all agree
// skips the filters and restarts its history), a temporal pass (running mean and variance of the
// rays with their count, the history clamped to a 17 x 17 Gaussian neighbourhood's mean +- one
// standard deviation, the variance boosted over the first 16 frames, the new frame weighing 1 down
// to 0.05 as the count reaches 32), then three a-trous passes of a 3 x 3 kernel at steps 1, 2, 4
// with the svgf stops (atrous.h); the first pass's output is the history.
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/denoisers/atrous.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/shaders.h"

namespace so {
namespace {

class FfxLight final : public LightDenoiser {
  public:
    FfxLight(RayFrame& frame, const EdgeStops& stops)
        : frame_(frame),
          classify_(frame.program("PASS_CLASSIFY", "", {shaders::ffx_glsl})),
          temporal_(
              frame.program("PASS_TEMPORAL", "", {shaders::reprojection_glsl, shaders::ffx_glsl})),
          temporalFbo_(makeFramebuffer()),
          atrous_(frame, stops, true) {
        // The temporal pass writes the moments (accum) and V with its variance (filterA) at once.
        const GLuint fbo = temporalFbo_.get();
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, frame.accum.texture.get(), 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, frame.filterA.texture.get(), 0);
        const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(fbo, 2, both);
    }
    GLuint denoise(PassClock& clock) override {
        classify(clock);
        clock.begin("temporal");
        frame_.bindHistory(temporal_);
        glBindTextureUnit(5, frame_.tiles.texture.get());  // read by the a-trous passes too
        glBindFramebuffer(GL_FRAMEBUFFER, temporalFbo_.get());
        glUseProgram(temporal_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        clock.end();
        return atrous_.run(clock, 3);  // FidelityFX's three passes
    }

  private:
    // Which 8 x 4 tiles skip the filters, drawn one fragment per tile.
    void classify(PassClock& clock) {
        clock.begin("classify");
        glViewport(0, 0, frame_.tilesW, frame_.tilesH);
        glBindTextureUnit(0, frame_.raw.texture.get());
        frame_.draw(frame_.tiles, classify_);
        glViewport(0, 0, frame_.width(), frame_.height());
        clock.end();
    }

    RayFrame& frame_;
    GlProgram classify_, temporal_;
    GlFramebuffer temporalFbo_;
    AtrousFilter atrous_;
};

class Ffx final : public Denoiser {
  public:
    static constexpr int kNumber = 3;
    static ParamTable params() {
        return {sigmaLuminanceParam(), sigmaNormalParam(), sigmaDepthParam()};
    }
    explicit Ffx(const ParamValues& v)
        : stops{v.real("sigma_luminance"), v.real("sigma_normal"), v.real("sigma_depth")} {}
    std::vector<std::string> passNames() const override {
        return {"classify", "temporal", "atrous"};
    }
    RayTarget result() const override { return RayTarget::Filter; }
    std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const override {
        return std::make_unique<FfxLight>(frame, stops);
    }

    EdgeStops stops;
};

}  // namespace

SO_REGISTER_DENOISER(Ffx, "ffx",
                     "AMD FidelityFX Shadow Denoiser's design: tile classification, temporal "
                     "moments, three a-trous passes");

}  // namespace so
