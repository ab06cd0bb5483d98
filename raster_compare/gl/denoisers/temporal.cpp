// temporal: a reprojected exponential history (the previous frame's result found through the
// previous camera, kept where the point lies on the same surface, else restarted), blended with
// weight `history`; a young history averages its frames equally.
#include "raster_compare/gl/denoisers/temporal.h"

#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/shaders.h"

namespace so {

ExponentialHistory::ExponentialHistory(RayFrame& frame, double history, double maxLength)
    : frame_(frame),
      program_(frame.program("PASS_TEMPORAL", "",
                             {shaders::reprojection_glsl, shaders::temporal_glsl})) {
    // The new frame's weight, in double: the float the shader gets is the one `alpha` gave.
    setFloat(program_.get(), "u_newWeight", 1.0 - history);
    setFloat(program_.get(), "u_maxLength", maxLength);
}

void ExponentialHistory::run(PassClock& clock) {
    clock.begin("temporal");
    frame_.bindHistory(program_);
    frame_.draw(frame_.accum, program_);
    clock.end();
}

namespace {

class TemporalLight final : public LightDenoiser {
  public:
    TemporalLight(RayFrame& frame, double history) : frame_(frame), history_(frame, history) {}
    GLuint denoise(PassClock& clock) override {
        history_.run(clock);
        frame_.keepHistory(0);
        return frame_.accum.texture.get();
    }

  private:
    RayFrame& frame_;
    ExponentialHistory history_;
};

class Temporal final : public Denoiser {
  public:
    static constexpr int kNumber = 1;
    static ParamTable params() { return {historyParam()}; }
    static Provenance provenance() {
        return {
            "our own: SVGF's temporal accumulation alone (Schied et al. HPG 2017, 4.1; "
            "reprojection.glsl as Falcor's SVGFReproject) as a denoiser, its history's length "
            "capped at 1024 where SVGF's is 32",
            Fidelity::Own};
    }
    explicit Temporal(const ParamValues& v) : history(v.real("history")) {}
    std::vector<std::string> passNames() const override { return {"temporal"}; }
    RayTarget result() const override { return RayTarget::Accum; }
    std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const override {
        return std::make_unique<TemporalLight>(frame, history);
    }

    double history;
};

}  // namespace

SO_REGISTER_DENOISER(Temporal, "temporal",
                     "a reprojected exponential history: the previous frame's result found "
                     "through the previous camera, kept where the point lies on the same surface");

}  // namespace so
