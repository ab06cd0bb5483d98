// rtg: Ray Tracing Gems chapter 13 (Boksansky, Wimmer, Bittner, "Ray Traced Shadows: Maintaining
// Real-Time Frame Rates"), as its sample code (Apress/ray-tracing-gems 424bf8d, Ch_13_.../
// dxrShadows) builds it with its defaults: adaptive sampling and the sampling matrix on, no global
// sample-count limit. Per pixel and light it keeps the last 4 frames' V (a visibility cache), their
// variation (max - min) and the last 4 ray counts. Before the rays, each pixel's count moves by one
// against the variation threshold (down only after three frames at one count), jumps to the most
// where reverse reprojection fails, and is 0 on 3 frames of 4 in the blocks of the sampling matrix
// where the filtered variation is 0 (the cache's V reused). After them, V is the 4 frames' mean,
// the variation is max-filtered (5 taps) and box-blurred (9 taps), and a separable Gaussian of 1 to
// 9 taps chosen by it, with binary depth and normal tests, filters V. The passes are rtg.glsl's.
#include <algorithm>

#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/shaders.h"

namespace so {
namespace {

// Defaults of the sample code (dxrShadows.h, its members' initialisers), not parameters here.
constexpr int kBlockSize = 8;                 // dxrShadows.h:212 mSamplingMatrixBlockSize
constexpr double kReprojectionDepth = 0.003;  // dxrShadows.h:121 mMaxReprojectionDepthDifference
constexpr double kDepthEpsilonMin = 0.003;    // dxrShadows.h:152
constexpr double kDepthEpsilonMax = 0.02;     // dxrShadows.h:153
constexpr double kNormalEpsilon = 0.9;        // dxrShadows.h:154 mFilteringDotNormalsEpsilon

struct RtgSettings {
    double threshold, maxVariation;
    bool samplingMatrix;
};

class RtgLight final : public LightDenoiser {
  public:
    RtgLight(RayFrame& frame, const RtgSettings& s);
    std::vector<uint8_t> sampleCounts(PassClock& clock, int spp) override;
    GLuint denoise(PassClock& clock) override;
    uint64_t memoryBytes() const override {
        // counts, variation and its temporary R32F; the caches RGBA32F.
        return uint64_t(frame_.width()) * uint64_t(frame_.height()) * (3 * 4 + 3 * 16);
    }

  private:
    GlProgram build(const char* pass) const;
    void bindPrevious();
    void filterVariation();
    void filterVisibility();

    RayFrame& frame_;
    ScreenTarget counts_, variation_, variationTmp_, variationCache_, prevVariation_, prevFiltered_;
    GlProgram count_, temporal_, variationPass_, filter_;
    GlFramebuffer temporalFbo_;
};

RtgLight::RtgLight(RayFrame& frame, const RtgSettings& s)
    : frame_(frame),
      counts_(GL_R32F, frame.width(), frame.height()),
      variation_(GL_R32F, frame.width(), frame.height()),
      variationTmp_(GL_R32F, frame.width(), frame.height()),
      variationCache_(GL_RGBA32F, frame.width(), frame.height()),
      prevVariation_(GL_RGBA32F, frame.width(), frame.height()),
      prevFiltered_(GL_RGBA32F, frame.width(), frame.height()),
      count_(build("PASS_COUNT")),
      temporal_(build("PASS_TEMPORAL")),
      variationPass_(build("PASS_VARIATION")),
      filter_(build("PASS_FILTER")),
      temporalFbo_(makeFramebuffer()) {
    const GLuint c = count_.get();
    setFloat(c, "u_threshold", s.threshold);
    setInt(c, "u_samplingMatrix", s.samplingMatrix ? 1 : 0);
    setInt(c, "u_blockSize", kBlockSize);
    for (GLuint p : {c, temporal_.get()}) {
        setFloat(p, "u_reprojectionDepth", kReprojectionDepth);
        setInt(p, "u_prevVariation", 6);
        setInt(p, "u_prevFiltered", 7);
        setInt(p, "u_counts", 5);
    }
    const GLuint f = filter_.get();
    setInt(f, "u_input", 0);
    setInt(f, "u_variation", 6);
    setFloat(f, "u_maxVariation", s.maxVariation);
    setFloat(f, "u_depthEpsilonMin", kDepthEpsilonMin);
    setFloat(f, "u_depthEpsilonMax", kDepthEpsilonMax);
    setFloat(f, "u_normalEpsilon", kNormalEpsilon);
    setInt(variationPass_.get(), "u_input", 0);
    // The second half of the ray generation shader writes the four at once.
    const GLuint fbo = temporalFbo_.get();
    const GLuint targets[4] = {frame.accum.texture.get(), variationCache_.texture.get(),
                               variation_.texture.get(), frame.filterA.texture.get()};
    GLenum buffers[4];
    for (int i = 0; i < 4; ++i) {
        glNamedFramebufferTexture(fbo, GLenum(GL_COLOR_ATTACHMENT0 + i), targets[i], 0);
        buffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
    }
    glNamedFramebufferDrawBuffers(fbo, 4, buffers);
}

GlProgram RtgLight::build(const char* pass) const {
    const auto bytes = [](const char* name, const ScreenTarget& t) {
        return "#define " + std::string(name) + " " + std::to_string(texelBytes(t.texture.get())) +
               "\n";
    };
    return frame_.program(pass,
                          bytes("COUNT_TEXEL_BYTES", counts_) +
                              bytes("VARIATION_TEXEL_BYTES", variation_) +
                              bytes("STATE_TEXEL_BYTES", variationCache_),
                          {shaders::rtg_glsl});
}

// Frame f - 1's caches of variation and counts and its filtered variation, on units 6 and 7.
void RtgLight::bindPrevious() {
    static_cast<void>(frame_.previous());
    glBindTextureUnit(6, prevVariation_.texture.get());
    glBindTextureUnit(7, prevFiltered_.texture.get());
}

std::vector<uint8_t> RtgLight::sampleCounts(PassClock& clock, int spp) {
    clock.begin("count");
    const int W = frame_.width(), H = frame_.height();
    if (const RayHistoryFrame* before = frame_.previous(); before && before->extra.size() == 2) {
        glTextureSubImage2D(prevVariation_.texture.get(), 0, 0, 0, W, H, GL_RGBA, GL_FLOAT,
                            before->extra[0].data());
        glTextureSubImage2D(prevFiltered_.texture.get(), 0, 0, 0, W, H, GL_RGBA, GL_FLOAT,
                            before->extra[1].data());
    }
    frame_.bindHistory(count_);
    bindPrevious();
    setInt(count_.get(), "u_maxCount", spp);
    setInt(count_.get(), "u_frameMod4", frame_.frameIndex() % 4);  // dxrShadows.cpp:612-613
    frame_.draw(counts_, count_);
    std::vector<float> read(size_t(W) * size_t(H));
    glGetTextureImage(counts_.texture.get(), 0, GL_RED, GL_FLOAT,
                      GLsizei(read.size() * sizeof(float)), read.data());
    std::vector<uint8_t> counts(read.size());
    for (size_t i = 0; i < read.size(); ++i)
        counts[i] = uint8_t(std::clamp(int(read[i]), 0, std::min(spp, 255)));
    clock.end();
    return counts;
}

// VariationFilteringPass run as dxrShadows.cpp:676-679 runs it: the maximum, then the average,
// each horizontally then vertically; the result in variation_.
void RtgLight::filterVariation() {
    const GLuint p = variationPass_.get();
    const ScreenTarget* from = &variation_;  // the temporal pass's variation
    const ScreenTarget* to = &variationTmp_;
    for (int maximum : {1, 0})
        for (int vertical : {0, 1}) {
            setInt(p, "u_maximum", maximum);
            glProgramUniform2i(p, glGetUniformLocation(p, "u_step"), 1 - vertical, vertical);
            glBindTextureUnit(0, from->texture.get());
            frame_.draw(*to, variationPass_);
            std::swap(from, to);
        }
}

// VisibilityFilteringPass: horizontal (filterA into filterB), then vertical (back into filterA).
void RtgLight::filterVisibility() {
    const GLuint p = filter_.get();
    setMat4(p, "u_clipFromLocal", frame_.camera().clipFromLocal());
    glBindTextureUnit(6, variation_.texture.get());
    glBindTextureUnit(1, frame_.camera().positionTexture());
    glBindTextureUnit(2, frame_.camera().normalTexture());
    for (int vertical : {0, 1}) {
        glProgramUniform2i(p, glGetUniformLocation(p, "u_step"), 1 - vertical, vertical);
        glBindTextureUnit(0, (vertical ? frame_.filterB : frame_.filterA).texture.get());
        frame_.draw(vertical ? frame_.filterA : frame_.filterB, filter_);
    }
}

GLuint RtgLight::denoise(PassClock& clock) {
    clock.begin("temporal");
    frame_.bindHistory(temporal_);
    bindPrevious();
    glBindTextureUnit(5, counts_.texture.get());
    glBindFramebuffer(GL_FRAMEBUFFER, temporalFbo_.get());
    glUseProgram(temporal_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    clock.end();
    clock.begin("variation");
    filterVariation();
    clock.end();
    clock.begin("filter");
    filterVisibility();
    clock.end();
    frame_.keepHistory(0, {variationCache_.texture.get(), variation_.texture.get()});
    return frame_.filterA.texture.get();
}

class Rtg final : public Denoiser {
  public:
    static constexpr int kNumber = 5;
    static ParamTable params() {
        return {{"variation_threshold", 0.1, 0.0, 1.0, false,
                 "a pixel's ray count goes up by one a frame while its variation (the mean of its "
                 "own over 4 frames and the filtered one) is above this, down by one below it "
                 "(Ray Tracing Gems 13, sample code dxrShadows.h:225 mTargetVariation: 0.1)"},
                {"max_variation", 0.4, 0.001, 1.0, false,
                 "the filtered variation at which the Gaussian reaches 9 taps (dxrShadows.h:155 "
                 "mFilteringMaxVariationLevel: 0.4)"},
                {"sampling_matrix",
                 1,
                 0,
                 1,
                 true,
                 "1: where the filtered variation is 0, a pixel traces on one frame of 4 (a 4 x 4 "
                 "matrix of 8 x 8-pixel blocks) and reuses its cache's V on the others "
                 "(dxrShadows.h:211 mEnableSamplingMatrix: on)",
                 {0, 1}}};
    }
    static Provenance provenance() {
        return {
            "Ray Tracing Gems ch. 13 (Boksansky, Wimmer, Bittner), sample code "
            "Apress/ray-tracing-gems 424bf8d, Ch_13_.../dxrShadows/Data/DXRShadows.rt.hlsl "
            "(rayGen, USE_ADAPTIVE_SAMPLING, APPLY_SAMPLING_MATRIX), "
            "VariationFilteringPass.ps.hlsl, VisibilityFilteringPass.ps.hlsl",
            Fidelity::Variant,
            {"rays traced by Embree on the CPU from the raster G-buffer's points "
             "(rays/shadow_rays.cpp), not DXR from the depth buffer",
             "the most rays a pixel traces is the technique's spp, where the sample code's "
             "is 5 (8 at high quality, dxrShadows.cpp:585); its least, 1, kept",
             "light points from a per-pixel Owen-scrambled Sobol sequence indexed by frame, "
             "not the sample's disk sample sets per 3 x 3 pixels and frame % 4",
             "V weighs the rays by the light's geometry term over its area (rect, disk, "
             "sphere) where the sample code samples a disk facing the point, rays weighing "
             "equally",
             "reprojection by the previous camera and the G-buffer's positions (the nearest "
             "previous texel's depth), where the sample's motion-vector pass samples the "
             "previous depth bilinearly",
             "the filter's normal test on the G-buffer's interpolated normals, where the "
             "sample reconstructs them from depth (CommonUtils.hlsl calculateNormal)",
             "one light a pass (the sample packs 8 into RGBA textures); the global sample-count "
             "limit (LIMIT_GLOBAL_SAMPLE_COUNT, off by default) not built"}};
    }
    explicit Rtg(const ParamValues& v)
        : settings{v.real("variation_threshold"), v.real("max_variation"),
                   v.integer("sampling_matrix") != 0} {}
    std::vector<std::string> passNames() const override {
        return {"count", "temporal", "variation", "filter"};
    }
    size_t passesBeforeTrace() const override { return 1; }
    RayTarget result() const override { return RayTarget::Filter; }
    std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const override {
        return std::make_unique<RtgLight>(frame, settings);
    }

    RtgSettings settings;
};

}  // namespace

SO_REGISTER_DENOISER(Rtg, "rtg",
                     "Ray Tracing Gems ch. 13: per-pixel ray counts adapted by one a frame to a "
                     "4-frame visibility variation, a Gaussian of 1 to 9 taps chosen by it");

}  // namespace so
