// svgf: Schied et al., "Spatiotemporal Variance-Guided Filtering", HPG 2017, step for step as
// NVIDIA's Falcor ships it (Source/RenderPasses/SVGFPass): the temporal accumulation of V and its
// first two moments (section 4.1, temporal.h; reprojection.glsl with Falcor's 3 x 3 fallback, the
// history's length capped at 32), the variance from the moments, or V and its moments
// cross-bilaterally filtered over 7 x 7 neighbours while the history is shorter than 4 frames
// (4.2, Falcor's SVGFFilterMoments), then
// `levels` a-trous levels of a 5 x 5 B3-spline kernel at steps 1, 2, 4, ... with edge stops on the
// normal (power `sigma_normal`), the depth (`sigma_depth`; the distance from the pixel's tangent
// plane in pixel footprints, SVGF's depth gradient in world terms) and V scaled by the 3 x
// 3-blurred standard deviation (`sigma_luminance`) (atrous.h); the first level's output is the
// next frame's history.
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/denoisers/atrous.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/denoisers/temporal.h"
#include "raster_compare/gl/shaders.h"

namespace so {
namespace {

class SvgfLight final : public LightDenoiser {
  public:
    SvgfLight(RayFrame& frame, double history, const EdgeStops& stops, int levels)
        : frame_(frame),
          history_(frame, history, 32),  // Falcor's SVGFReproject.ps.slang:216
          variance_(frame.program("PASS_VARIANCE", "", {shaders::svgf_glsl})),
          atrous_(frame, stops),
          levels_(levels) {
        const GLuint vp = variance_.get();
        setFloat(vp, "u_sigmaNormal", stops.normal);
        setFloat(vp, "u_sigmaLuminance", stops.luminance);
        setFloat(vp, "u_sigmaDepth", stops.depth);
    }
    GLuint denoise(PassClock& clock) override {
        history_.run(clock);
        clock.begin("variance");
        glBindTextureUnit(0, frame_.accum.texture.get());
        frame_.draw(frame_.filterA, variance_);
        clock.end();
        return atrous_.run(clock, levels_);
    }

  private:
    RayFrame& frame_;
    ExponentialHistory history_;
    GlProgram variance_;
    AtrousFilter atrous_;
    int levels_;
};

class Svgf final : public Denoiser {
  public:
    static constexpr int kNumber = 2;
    static ParamTable params() {
        return {historyParam(),
                {"levels", 5, 1, 8, true,
                 "a-trous levels, steps 1, 2, 4, ... (SVGF 4.2: 5; Falcor's SVGFPass.h:71 has 4)"},
                sigmaLuminanceParam(),
                sigmaNormalParam(),
                sigmaDepthParam()};
    }
    static Provenance provenance() {
        return {
            "Schied et al., \"Spatiotemporal Variance-Guided Filtering\", HPG 2017, sections "
            "4.1-4.2, as NVIDIA Falcor eb540f67 ships it (Source/RenderPasses/SVGFPass: "
            "SVGFReproject, SVGFFilterMoments, SVGFAtrous)",
            Fidelity::Variant,
            {"the paper's defaults (alpha 0.2 for V and moments, 5 levels, sigma_luminance 4, "
             "the first level fed back) where Falcor's SVGFPass.h:71-77 has alpha 0.05 (0.2 "
             "for the moments), 4 iterations, phiColor 10 and feedback tap 1",
             "the same surface is a texel within one pixel footprint of the point's tangent "
             "plane (four along it) where Falcor compares linear depth against its screen "
             "gradient (x 10) and the normals' distance (x 16); the depth stops measure the "
             "distance from the tangent plane in pixel footprints, Falcor's view-depth "
             "difference over its gradient",
             "reprojects by the camera's motion only (no per-mesh motion vectors)",
             "filters V, one channel, where Falcor filters RGB illumination demodulated by "
             "albedo (its luminance driving the stops)"}};
    }
    explicit Svgf(const ParamValues& v)
        : history(v.real("history")),
          levels(v.integer("levels")),
          stops{v.real("sigma_luminance"), v.real("sigma_normal"), v.real("sigma_depth")} {}
    std::vector<std::string> passNames() const override {
        return {"temporal", "variance", "atrous"};
    }
    RayTarget result() const override { return RayTarget::Filter; }
    std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const override {
        return std::make_unique<SvgfLight>(frame, history, stops, levels);
    }

    double history;
    int levels;
    EdgeStops stops;
};

}  // namespace

SO_REGISTER_DENOISER(Svgf, "svgf",
                     "Schied et al. HPG 2017: temporal moments and variance-guided a-trous");

}  // namespace so
