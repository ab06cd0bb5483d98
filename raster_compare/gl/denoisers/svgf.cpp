// svgf: Schied et al., "Spatiotemporal Variance-Guided Filtering", HPG 2017: the temporal
// accumulation of V and its first two moments (section 4.1, temporal.h), the variance from the
// moments, or over 7 x 7 neighbours while the history is shorter than 4 frames (4.2), then
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
          history_(frame, history),
          variance_(frame.program("PASS_VARIANCE", "", {shaders::svgf_glsl})),
          atrous_(frame, stops, false),
          levels_(levels) {
        setFloat(variance_.get(), "u_sigmaNormal", stops.normal);
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
                 "a-trous levels, steps 1, 2, 4, ... (SVGF 4.2: 5; ffx runs 3, its FidelityFX "
                 "passes)"},
                sigmaLuminanceParam(),
                sigmaNormalParam(),
                sigmaDepthParam()};
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
