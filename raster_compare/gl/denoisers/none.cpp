// none: the rays' estimate as it is.
#include "raster_compare/gl/denoisers/denoiser.h"

namespace so {
namespace {

class NoneLight final : public LightDenoiser {
  public:
    explicit NoneLight(RayFrame& frame) : frame_(frame) {}
    GLuint denoise(PassClock& /*clock*/) override { return frame_.raw.texture.get(); }

  private:
    RayFrame& frame_;
};

class NoDenoiser final : public Denoiser {
  public:
    static constexpr int kNumber = 0;
    static ParamTable params() { return {}; }
    static Provenance provenance() {
        return {
            "no denoiser: the rays' Monte Carlo estimate as traced (the baseline every "
            "denoiser is measured against)",
            Fidelity::Faithful};
    }
    explicit NoDenoiser(const ParamValues& /*v*/) {}
    std::vector<std::string> passNames() const override { return {}; }
    bool keepsHistory() const override { return false; }
    RayTarget result() const override { return RayTarget::Raw; }
    std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const override {
        return std::make_unique<NoneLight>(frame);
    }
};

}  // namespace

SO_REGISTER_DENOISER(NoDenoiser, "none", "the rays' estimate as it is");

}  // namespace so
