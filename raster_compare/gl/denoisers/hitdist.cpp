// hitdist: a design of ours (called `penumbra` before format 8, and wrongly credited to Ray Tracing
// Gems chapter 13, whose design is `rtg`): the temporal history (temporal.h), filtered over a disk
// whose radius is the penumbra's estimated half-width in pixels: w = light size x d_blocker /
// (d_light - d_blocker) by similar triangles (PCSS's estimate, Fernando 2005), d_blocker the mean
// distance of the blocked rays around the pixel (the rays trace closest hits for it), at most
// `max_radius` pixels.
#include <string>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/denoisers/denoiser.h"
#include "raster_compare/gl/denoisers/temporal.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {
namespace {

struct HitDistanceFilter {
    double maxRadius, radiusScale, sigmaNormal;
    int taps, searchRadius;
};

class HitDistanceLight final : public LightDenoiser {
  public:
    HitDistanceLight(RayFrame& frame, double history, const HitDistanceFilter& f)
        : frame_(frame),
          history_(frame, history),
          program_(frame.program("PASS_HITDIST",
                                 "#define SEARCH_RADIUS " + std::to_string(f.searchRadius) +
                                     "\n#define PENUMBRA_TAPS " + std::to_string(f.taps) + "\n",
                                 {shaders::hitdist_glsl})) {
        const GLuint pp = program_.get();
        setInt(pp, "u_raw", 3);  // beside the accumulation on unit 0
        const Light& light = frame.light();
        const LocalFrame& local = frame.scene().frame();
        setFloat(pp, "u_lsLightSize", isAreaLight(light) ? local.lsLength(lightWidth(light)) : 0.0);
        setVec3(pp, "u_lsLightCenter", local.lsFromWs(light.wsPosition));
        setFloat(pp, "u_maxRadius", f.maxRadius);
        setFloat(pp, "u_radiusScale", f.radiusScale);
        setFloat(pp, "u_sigmaNormal", f.sigmaNormal);
    }
    GLuint denoise(PassClock& clock) override {
        history_.run(clock);
        clock.begin("hitdist");
        glBindTextureUnit(0, frame_.accum.texture.get());
        glBindTextureUnit(3, frame_.raw.texture.get());
        frame_.draw(frame_.filterA, program_);
        clock.end();
        frame_.keepHistory(0);
        return frame_.filterA.texture.get();
    }

  private:
    RayFrame& frame_;
    ExponentialHistory history_;
    GlProgram program_;
};

class HitDistance final : public Denoiser {
  public:
    static constexpr int kNumber = 4;
    static ParamTable params() {
        return {historyParam(),
                sigmaNormalParam(),
                {"max_radius", 16, 0, 64, false,
                 "the filter's largest radius in pixels (bounded for its cost)"},
                {"radius_scale", 0.25, 0.01, 4, false,
                 "the filter's radius in half-widths of the estimated penumbra (a disk as wide "
                 "as the penumbra blurs its ends: 0.25 measured best on lambert.h's rect light "
                 "over a square, 16 frames at 1 ray)"},
                {"taps", 32, 4, 256, true, "taps of the disk filter, on a golden-angle spiral"},
                {"search_radius", 8, 1, 32, true,
                 "half-width in pixels of the window whose blocked rays give the blocker "
                 "distance (every other pixel)"}};
    }
    static Provenance provenance() {
        return {
            "our own: the blocker-distance penumbra estimate of PCSS (Fernando, \"Percentage-"
            "Closer Soft Shadows\", SIGGRAPH 2005 sketch) from the rays' hit distances, over "
            "SVGF's temporal accumulation (Schied et al. HPG 2017, 4.1)",
            Fidelity::Own};
    }
    explicit HitDistance(const ParamValues& v)
        : history(v.real("history")),
          filter{v.real("max_radius"), v.real("radius_scale"), v.real("sigma_normal"),
                 v.integer("taps"), v.integer("search_radius")} {}
    std::vector<std::string> passNames() const override { return {"temporal", "hitdist"}; }
    bool needsHitDistance() const override { return true; }
    RayTarget result() const override { return RayTarget::Filter; }
    std::unique_ptr<LightDenoiser> setUp(RayFrame& frame) const override {
        return std::make_unique<HitDistanceLight>(frame, history, filter);
    }

    double history;
    HitDistanceFilter filter;
};

}  // namespace

SO_REGISTER_DENOISER(HitDistance, "hitdist",
                     "ours: the temporal history filtered over a disk as wide as the penumbra "
                     "estimated from the rays' blocker distance (called penumbra before format 8)");

}  // namespace so
