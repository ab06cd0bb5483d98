// raytraced: ray-traced shadows and their denoisers (issue 53). Each frame, from every pixel's
// point of the camera pass (its G-buffer, read back: the pixels a GPU would shade), `spp` shadow
// rays to points on the light, traced by Embree on the CPU (shadow_rays.h: the work RT cores do on
// a GPU; an Owen-scrambled Sobol sequence per pixel advanced with the sequence's frame index); the
// estimate is uploaded as a texture and denoised by full-screen GLSL passes (fragment passes, so
// the counted frame counts their fragments, taps and bytes as every other family's):
// - `none`: the rays' estimate as it is.
// - `temporal`: a reprojected exponential history (the previous frame's result found through the
//   previous camera, kept where the point lies on the same surface, else restarted), blended with
//   weight `alpha` for the new frame; a young history averages its frames equally.
// - `svgf`: Schied et al., "Spatiotemporal Variance-Guided Filtering", HPG 2017: the same temporal
//   accumulation of V and its first two moments (section 4.1), the variance from the moments, or
//   over 7 x 7 neighbours while the history is shorter than 4 frames (4.2), then `levels` a-trous
//   levels of a 5 x 5 B3-spline kernel at steps 1, 2, 4, ... with edge stops on the normal (power
//   `sigma_normal`), the depth (`sigma_depth`; the distance from the pixel's tangent plane in
//   pixel footprints, SVGF's depth gradient in world terms) and V scaled by the 3 x 3-blurred
//   standard deviation (`sigma_luminance`); the first level's output is the next frame's history.
// - `ffx`: the design of AMD's FidelityFX Shadow Denoiser (MIT; GPUOpen-Effects/FidelityFX-
//   Denoiser, ffx-shadows-dnsr; written here from its description, for one ray a pixel): tile
//   classification (8 x 4 tiles, its ray masks' size: a tile whose rays and its neighbour tiles'
//   rays all agree skips the filters and restarts its history), a temporal pass (running mean and
//   variance of the rays with their count, the history clamped to a 17 x 17 Gaussian
//   neighbourhood's mean +- one standard deviation, the variance boosted over the first 16 frames,
//   the new frame weighing 1 down to 0.05 as the count reaches 32), then three a-trous passes of a
//   3 x 3 kernel at steps 1, 2, 4 with the svgf stops; the first pass's output is the history.
// - `penumbra`: Ray Tracing Gems, chapter 13 (Boksansky, Wimmer, Bittner, "Ray Traced Shadows:
//   Maintaining Real-Time Frame Rates", 2019): the temporal history, filtered over a disk whose
//   radius is the penumbra's estimated half-width in pixels: w = light size x d_blocker /
//   (d_light - d_blocker) by similar triangles, d_blocker the mean distance of the blocked rays
//   around the pixel (the rays trace closest hits for it), at most `max_radius` pixels.
// The history lives across the renders of a sequence (compare --sequence, RasterOptions::
// frameIndex): frame f reads what frame f - 1 left, so a repeated render of a frame (warm-up,
// timed frames) gives the same image. Moving meshes restart their history (the raster path is not
// given their motion); a moving camera reprojects.
#include <cmath>
#include <map>
#include <mutex>
#include <optional>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/rays/shadow_rays.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

enum class Denoiser { None, Temporal, Svgf, Ffx, Penumbra };

// What frame f of a light left for frame f + 1, on the CPU (GL objects do not outlive a render).
struct RayHistoryFrame {
    int width = 0, height = 0;
    std::vector<float> history;     // RGBA, GL row order: V, first and second moments, length
    std::vector<float> lsPosition;  // RGBA, the camera pass's positions in `frame`
    glm::dmat4 clipFromLocal{1.0};
    LocalFrame frame;
};

// The frames kept per light: frame f and f - 1, so that every render of frame f reads f - 1.
class RayHistoryStore {
  public:
    std::optional<RayHistoryFrame> before(const std::string& light, int frameIndex, int width,
                                          int height) const {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto l = frames_.find(light);
        if (l == frames_.end()) return std::nullopt;
        const auto f = l->second.find(frameIndex - 1);
        if (f == l->second.end() || f->second.width != width || f->second.height != height)
            return std::nullopt;
        return f->second;
    }
    void keep(const std::string& light, int frameIndex, RayHistoryFrame frame) {
        std::lock_guard<std::mutex> lock(mutex_);
        std::map<int, RayHistoryFrame>& byFrame = frames_[light];
        byFrame.erase(byFrame.begin(), byFrame.lower_bound(frameIndex - 1));
        byFrame[frameIndex] = std::move(frame);
    }

  private:
    mutable std::mutex mutex_;
    std::map<std::string, std::map<int, RayHistoryFrame>> frames_;
};

class Raytraced final : public Technique {
  public:
    static constexpr const char* kFamily = "ray tracing";
    static ParamTable params() {
        const auto needs = [](ParamSpec spec, const char* setting) {
            spec.needs = setting;
            return spec;
        };
        return {
            {"spp",
             1,
             1,
             256,
             true,
             "shadow rays per pixel and frame, to points of a per-pixel scrambled Sobol sequence "
             "on the light (issue 53: 1, 2, 4 ...; FidelityFX's denoiser is built for 1)",
             {},
             true},
            methodParam("denoiser", 0, {"none", "temporal", "svgf", "ffx", "penumbra"},
                        "none: the rays' estimate; temporal: a reprojected exponential history; "
                        "svgf: Schied et al. HPG 2017, temporal moments and variance-guided "
                        "a-trous; ffx: AMD FidelityFX Shadow Denoiser's design, tile "
                        "classification, temporal moments, three a-trous passes; penumbra: "
                        "the temporal history filtered over a disk as wide as the penumbra "
                        "estimated from the blocker distance (Ray Tracing Gems chapter 13)"),
            needs({"alpha", 0.2, 0.01, 1, false,
                   "temporal, svgf: the new frame's weight in the exponential history (SVGF "
                   "section 4.1: 0.2); a history younger than 1 / alpha frames averages them "
                   "equally"},
                  "denoiser=temporal|svgf|penumbra"),
            needs({"levels", 5, 1, 8, true,
                   "svgf: a-trous levels, steps 1, 2, 4, ... (SVGF 4.2: 5; ffx runs 3, its "
                   "FidelityFX passes)"},
                  "denoiser=svgf"),
            needs({"sigma_luminance", 4, 0.01, 1000, false,
                   "svgf, ffx: V stop, in standard deviations of the 3 x 3-blurred variance "
                   "(SVGF 4.2: 4)"},
                  "denoiser=svgf|ffx"),
            needs({"sigma_normal", 128, 1, 1024, false,
                   "svgf, ffx: normal stop, the power of the normals' cosine (SVGF 4.2: 128)"},
                  "denoiser=svgf|ffx|penumbra"),
            needs({"sigma_depth", 1, 0.01, 1000, false,
                   "svgf, ffx: depth stop, the distance from the pixel's tangent plane in pixel "
                   "footprints per pixel of distance (SVGF 4.2: 1, on its depth gradient)"},
                  "denoiser=svgf|ffx"),
            needs({"max_radius", 16, 0, 64, false,
                   "penumbra: the filter's largest radius in pixels (Ray Tracing Gems 13: the "
                   "kernel is bounded for its cost)"},
                  "denoiser=penumbra"),
            needs({"radius_scale", 0.25, 0.01, 4, false,
                   "penumbra: the filter's radius in half-widths of the estimated penumbra (a "
                   "disk as wide as the penumbra blurs its ends: 0.25 measured best on lambert.h's "
                   "rect light over a square, 16 frames at 1 ray)"},
                  "denoiser=penumbra"),
            needs({"taps", 32, 4, 256, true,
                   "penumbra: taps of the disk filter, on a golden-angle spiral"},
                  "denoiser=penumbra"),
            needs({"search_radius", 8, 1, 32, true,
                   "penumbra: half-width in pixels of the window whose blocked rays give the "
                   "blocker distance (every other pixel)"},
                  "denoiser=penumbra")};
    }
    explicit Raytraced(const ParamValues& v)
        : Technique(v),
          spp(v.integer("spp")),
          denoiser(Denoiser(v.integer("denoiser"))),
          alpha(v.real("alpha")),
          levels(v.integer("levels")),
          sigmaLuminance(v.real("sigma_luminance")),
          sigmaNormal(v.real("sigma_normal")),
          sigmaDepth(v.real("sigma_depth")),
          maxRadius(v.real("max_radius")),
          radiusScale(v.real("radius_scale")),
          taps(v.integer("taps")),
          searchRadius(v.integer("search_radius")) {}
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override;

    int spp;
    Denoiser denoiser;
    double alpha;
    int levels;
    double sigmaLuminance, sigmaNormal, sigmaDepth;
    double maxRadius, radiusScale;
    int taps, searchRadius;
    mutable RayHistoryStore store;
};

// The BVH, shared by the lights of one render.
struct SharedTracer : SetUpShared {
    explicit SharedTracer(const GpuScene& scene) : tracer(scene.scene(), scene.frame()) {}
    ShadowRayTracer tracer;
};

// A full-screen target of its own.
struct ScreenTarget {
    ScreenTarget(GLenum format, int width, int height)
        : texture(makeTexture2D(format, width, height)), fbo(makeFramebuffer()) {
        glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, texture.get(), 0);
    }
    GlTexture texture;
    GlFramebuffer fbo;
};

class RaytracedLight final : public LightTechnique {
  public:
    RaytracedLight(const Raytraced& technique, const LightSetup& setup);
    std::vector<std::string> passNames() const override;
    void renderLightPasses(PassClock& /*clock*/) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override;

  private:
    GlProgram program(const char* pass, const std::string& defines = "") const;
    void trace(PassClock& clock);
    void classify(PassClock& clock);
    void temporal(PassClock& clock, const std::optional<RayHistoryFrame>& before);
    GLuint atrous(PassClock& clock, int levels);
    void drawInto(const ScreenTarget& target, const GlProgram& p) const;
    void keepHistory(GLuint firstLevel);

    const Raytraced& t_;
    const Light& light_;
    const GpuScene& scene_;
    const CameraPass& camera_;
    int frameIndex_;
    std::shared_ptr<const SharedTracer> tracer_;
    int W_, H_;
    std::vector<float> position_, normal_;  // this frame's G-buffer, GL row order
    ScreenTarget raw_, accum_, prevHistory_, prevPosition_, filterA_, filterB_;
    // ffx: one texel per 8 x 4 tile (1: skipped), and the temporal pass's two outputs (accum_,
    // filterA_).
    int tilesW_, tilesH_;
    ScreenTarget tiles_;
    GlFramebuffer ffxTemporalFbo_;
    GlProgram classifyProg_, temporalProg_, varianceProg_, atrousProg_, penumbraProg_, resolveProg_;
    uint64_t lastRays_ = 0, lastPixels_ = 0;
};

std::unique_ptr<LightTechnique> Raytraced::setUp(const LightSetup& setup) const {
    return std::make_unique<RaytracedLight>(*this, setup);
}

RaytracedLight::RaytracedLight(const Raytraced& technique, const LightSetup& setup)
    : t_(technique),
      light_(setup.light),
      scene_(setup.scene),
      camera_(setup.camera),
      frameIndex_(setup.frameIndex),
      W_(setup.camera.width()),
      H_(setup.camera.height()),
      raw_(GL_RG32F, W_, H_),
      accum_(GL_RGBA32F, W_, H_),
      prevHistory_(GL_RGBA32F, W_, H_),
      prevPosition_(GL_RGBA32F, W_, H_),
      filterA_(GL_RG32F, W_, H_),
      filterB_(GL_RG32F, W_, H_),
      tilesW_((W_ + 7) / 8),
      tilesH_((H_ + 3) / 4),
      tiles_(GL_R32F, tilesW_, tilesH_) {
    const std::string key = "raytraced.bvh";
    if (setup.shared && setup.shared->count(key))
        tracer_ = std::static_pointer_cast<const SharedTracer>(setup.shared->at(key));
    else {
        tracer_ = std::make_shared<const SharedTracer>(setup.scene);
        if (setup.shared) (*setup.shared)[key] = tracer_;
    }
    resolveProg_ = program("PASS_RESOLVE");
    if (t_.denoiser == Denoiser::None) return;
    const bool ffx = t_.denoiser == Denoiser::Ffx;
    temporalProg_ = program("PASS_TEMPORAL", ffx ? "#define FFX\n" : "");
    setFloat(temporalProg_.get(), "u_alpha", t_.alpha);
    if (t_.denoiser == Denoiser::Temporal) return;
    if (t_.denoiser == Denoiser::Penumbra) {
        penumbraProg_ = program("PASS_PENUMBRA",
                                "#define SEARCH_RADIUS " + std::to_string(t_.searchRadius) +
                                    "\n#define PENUMBRA_TAPS " + std::to_string(t_.taps) + "\n");
        const GLuint pp = penumbraProg_.get();
        setInt(pp, "u_raw", 3);  // beside the accumulation on unit 0
        const LocalFrame& frame = setup.scene.frame();
        setFloat(pp, "u_lsLightSize",
                 isAreaLight(light_) ? frame.lsLength(lightWidth(light_)) : 0.0);
        setVec3(pp, "u_lsLightCenter", frame.lsFromWs(light_.wsPosition));
        setFloat(pp, "u_maxRadius", t_.maxRadius);
        setFloat(pp, "u_radiusScale", t_.radiusScale);
        setFloat(pp, "u_sigmaNormal", t_.sigmaNormal);
        return;
    }
    if (ffx) {
        classifyProg_ = program("PASS_CLASSIFY");
        ffxTemporalFbo_ = makeFramebuffer();
        const GLuint fbo = ffxTemporalFbo_.get();
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, accum_.texture.get(), 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, filterA_.texture.get(), 0);
        const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(fbo, 2, both);
    } else {
        varianceProg_ = program("PASS_VARIANCE");
        setFloat(varianceProg_.get(), "u_sigmaNormal", t_.sigmaNormal);
    }
    atrousProg_ = program("PASS_ATROUS", ffx ? "#define TILE_SKIP\n#define KERNEL_3X3\n" : "");
    const GLuint ap = atrousProg_.get();
    setFloat(ap, "u_sigmaLuminance", t_.sigmaLuminance);
    setFloat(ap, "u_sigmaNormal", t_.sigmaNormal);
    setFloat(ap, "u_sigmaDepth", t_.sigmaDepth);
}

// One pass's program, its samplers on fixed units: 0 the pass's input, 1 position, 2 normal,
// 3 and 4 the previous frame's history and positions, 5 ffx's tiles.
GlProgram RaytracedLight::program(const char* pass, const std::string& defines) const {
    const auto bytes = [](const char* name, GLuint texture) {
        return "#define " + std::string(name) + " " + std::to_string(texelBytes(texture)) + "\n";
    };
    GlProgram p = buildProgram(
        "#define " + std::string(pass) + "\n" + defines + camera_.texelBytesDefines() +
            bytes("TILE_TEXEL_BYTES", tiles_.texture.get()) +
            bytes("RAW_TEXEL_BYTES", raw_.texture.get()) +
            bytes("ACCUM_TEXEL_BYTES", accum_.texture.get()) +
            bytes("FILTER_TEXEL_BYTES", filterA_.texture.get()) +
            bytes("RESULT_TEXEL_BYTES", t_.denoiser == Denoiser::Temporal ? accum_.texture.get()
                                                                          : filterA_.texture.get()),
        shaders::fullscreen_vert, {shaders::raytraced_glsl});
    const GLuint g = p.get();
    for (const char* input : {"u_raw", "u_accum", "u_filter", "u_result"}) setInt(g, input, 0);
    setInt(g, "u_position", 1);
    setInt(g, "u_normal", 2);
    setInt(g, "u_prevHistory", 3);
    setInt(g, "u_prevPosition", 4);
    setInt(g, "u_tiles", 5);
    setVec3(g, "u_lsEye", camera_.lsEye());
    setFloat(g, "u_pixelScale", camera_.pixelScale());
    return p;
}

std::vector<std::string> RaytracedLight::passNames() const {
    switch (t_.denoiser) {
        case Denoiser::None:
            return {"trace", "resolve"};
        case Denoiser::Temporal:
            return {"trace", "temporal", "resolve"};
        case Denoiser::Svgf:
            return {"trace", "temporal", "variance", "atrous", "resolve"};
        case Denoiser::Penumbra:
            return {"trace", "temporal", "penumbra", "resolve"};
        case Denoiser::Ffx:
            break;
    }
    return {"trace", "classify", "temporal", "atrous", "resolve"};
}

// The G-buffer read back, the rays traced, their estimate uploaded.
void RaytracedLight::trace(PassClock& clock) {
    clock.begin("trace");
    const size_t texels = size_t(W_) * size_t(H_);
    position_.resize(4 * texels);
    normal_.resize(4 * texels);
    const auto bytes = GLsizei(4 * texels * sizeof(float));
    glGetTextureImage(camera_.positionTexture(), 0, GL_RGBA, GL_FLOAT, bytes, position_.data());
    glGetTextureImage(camera_.normalTexture(), 0, GL_RGBA, GL_FLOAT, bytes, normal_.data());
    ShadowRaySettings settings;
    settings.spp = t_.spp;
    settings.frameIndex = frameIndex_;
    settings.hitDistance = t_.denoiser == Denoiser::Penumbra;
    const ShadowRayFrame frame =
        tracer_->tracer.trace({W_, H_, position_.data(), normal_.data()}, light_, settings);
    glTextureSubImage2D(raw_.texture.get(), 0, 0, 0, W_, H_, GL_RG, GL_FLOAT,
                        frame.visibilityAndHit.data());
    lastRays_ = frame.raysTraced;
    lastPixels_ = frame.pixelsTraced;
    clock.addRays(frame.raysTraced);
    clock.end();
}

void RaytracedLight::drawInto(const ScreenTarget& target, const GlProgram& p) const {
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.get());
    glUseProgram(p.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

// V and its moments accumulated over the reprojected history into accum_.
void RaytracedLight::temporal(PassClock& clock, const std::optional<RayHistoryFrame>& before) {
    clock.begin("temporal");
    const GLuint tp = temporalProg_.get();
    setInt(tp, "u_haveHistory", before ? 1 : 0);
    if (before) {
        glTextureSubImage2D(prevHistory_.texture.get(), 0, 0, 0, W_, H_, GL_RGBA, GL_FLOAT,
                            before->history.data());
        glTextureSubImage2D(prevPosition_.texture.get(), 0, 0, 0, W_, H_, GL_RGBA, GL_FLOAT,
                            before->lsPosition.data());
        // previous local = (ws - c') 2^-e' with ws = ls 2^e + c: a scale and an offset.
        const LocalFrame& now = scene_.frame();
        setFloat(tp, "u_prevScale", std::ldexp(1.0, now.exponent - before->frame.exponent));
        setVec3(tp, "u_prevOffset", before->frame.lsFromWs(now.wsCenter));
        setMat4(tp, "u_prevClipFromLocal", before->clipFromLocal);
    }
    glBindTextureUnit(0, raw_.texture.get());
    glBindTextureUnit(1, camera_.positionTexture());
    glBindTextureUnit(2, camera_.normalTexture());
    glBindTextureUnit(3, prevHistory_.texture.get());
    glBindTextureUnit(4, prevPosition_.texture.get());
    if (t_.denoiser == Denoiser::Ffx) {
        glBindTextureUnit(5, tiles_.texture.get());
        glBindFramebuffer(GL_FRAMEBUFFER, ffxTemporalFbo_.get());
        glUseProgram(temporalProg_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    } else {
        drawInto(accum_, temporalProg_);
    }
    clock.end();
}

// ffx: which 8 x 4 tiles skip the filters, drawn one fragment per tile.
void RaytracedLight::classify(PassClock& clock) {
    clock.begin("classify");
    glViewport(0, 0, tilesW_, tilesH_);
    glBindTextureUnit(0, raw_.texture.get());
    drawInto(tiles_, classifyProg_);
    glViewport(0, 0, W_, H_);
    clock.end();
}

// The a-trous levels over filterA_ (V and its variance); returns the texture holding the result,
// and keeps the first level's output as the history's V.
GLuint RaytracedLight::atrous(PassClock& clock, int levels) {
    const ScreenTarget* in = &filterA_;
    const ScreenTarget* out = &filterB_;
    GLuint firstLevel = 0;
    for (int level = 0; level < levels; ++level) {
        clock.begin("atrous");
        setInt(atrousProg_.get(), "u_step", 1 << level);
        glBindTextureUnit(0, in->texture.get());
        drawInto(*out, atrousProg_);
        clock.end();
        if (level == 0) firstLevel = out->texture.get();
        std::swap(in, out);
        if (level == 0) keepHistory(firstLevel);
    }
    return in->texture.get();
}

// What the next frame reprojects: the accumulated moments and length, with V from `firstLevel`
// (SVGF feeds the first a-trous level back) or the accumulation's own (0).
void RaytracedLight::keepHistory(GLuint firstLevel) {
    RayHistoryFrame f;
    f.width = W_;
    f.height = H_;
    const size_t texels = size_t(W_) * size_t(H_);
    f.history.resize(4 * texels);
    glGetTextureImage(accum_.texture.get(), 0, GL_RGBA, GL_FLOAT,
                      GLsizei(f.history.size() * sizeof(float)), f.history.data());
    if (firstLevel) {
        std::vector<float> rg(2 * texels);
        glGetTextureImage(firstLevel, 0, GL_RG, GL_FLOAT, GLsizei(rg.size() * sizeof(float)),
                          rg.data());
        for (size_t i = 0; i < texels; ++i) f.history[4 * i] = rg[2 * i];
    }
    f.lsPosition = position_;
    f.clipFromLocal = camera_.clipFromLocal();
    f.frame = scene_.frame();
    t_.store.keep(light_.name, frameIndex_, std::move(f));
}

void RaytracedLight::renderVisibility(PassClock& clock) {
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    trace(clock);
    glDisable(GL_DEPTH_TEST);
    glBindTextureUnit(1, camera_.positionTexture());
    glBindTextureUnit(2, camera_.normalTexture());
    GLuint result = raw_.texture.get();
    if (t_.denoiser == Denoiser::Ffx) classify(clock);
    if (t_.denoiser != Denoiser::None)
        temporal(clock, t_.store.before(light_.name, frameIndex_, W_, H_));
    switch (t_.denoiser) {
        case Denoiser::None:
            break;
        case Denoiser::Temporal:
            result = accum_.texture.get();
            keepHistory(0);
            break;
        case Denoiser::Svgf:
            clock.begin("variance");
            glBindTextureUnit(0, accum_.texture.get());
            drawInto(filterA_, varianceProg_);
            clock.end();
            result = atrous(clock, t_.levels);
            break;
        case Denoiser::Ffx:
            result = atrous(clock, 3);  // FidelityFX's three passes
            break;
        case Denoiser::Penumbra:
            clock.begin("penumbra");
            glBindTextureUnit(0, accum_.texture.get());
            glBindTextureUnit(3, raw_.texture.get());
            drawInto(filterA_, penumbraProg_);
            clock.end();
            keepHistory(0);
            result = filterA_.texture.get();
            break;
    }
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

uint64_t RaytracedLight::memoryBytes() const {
    // raw and two filter targets RG32F; accumulation and the previous frame's history and
    // positions RGBA32F; the tiles R32F.
    return uint64_t(W_) * uint64_t(H_) * (3 * 8 + 3 * 16) +
           uint64_t(tilesW_) * uint64_t(tilesH_) * 4;
}

}  // namespace

SO_REGISTER_TECHNIQUE(Raytraced, "raytraced",
                      "shadow rays from the G-buffer traced by Embree (spp a frame), denoised: "
                      "none, temporal, svgf, ffx or penumbra");

}  // namespace so
