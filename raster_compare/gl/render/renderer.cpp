#include "raster_compare/gl/render/renderer.h"

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "core/channels.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/resolves/resolve.h"
#include "raster_compare/gl/time/temporal_state.h"

namespace so {

namespace {

// One light in the frame: its target, the technique's passes for it and, where the technique
// resolves its frames over time, the light's resolve (resolves/resolve.h), which runs after them.
struct FrameLight {
    const Light* light;
    LightTarget target;
    std::unique_ptr<LightTechnique> passes;
    std::unique_ptr<LightResolve> resolve = nullptr;
};

// The frame: every light's own passes, the camera pass, every light's visibility pass, recorded
// by `recorder` (timed, or counted with the counting builds' programs). Returns the wall time in
// ms (GL finished).
double renderFrame(const CameraPass& camera, std::vector<FrameLight>& lights,
                   PassRecorder& recorder, bool counted = false) {
    const auto t0 = std::chrono::steady_clock::now();
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    for (FrameLight& l : lights) {
        PassClock clock(recorder, l.light->name);
        l.passes->renderLightPasses(clock);
    }
    recorder.begin("camera");
    camera.render(counted);
    recorder.end();
    // The visibility passes shade exactly the surfaces the camera pass found.
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
    for (FrameLight& l : lights) {
        PassClock clock(recorder, l.light->name);
        l.target.bindAndClear();
        l.passes->renderVisibility(clock);
        if (l.resolve) l.resolve->resolve(clock);
    }
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The receivers the camera sees, rendered once for every technique that asks (fit=receivers).
std::optional<Bounds3d> receiverBounds(const CameraPass& camera,
                                       const std::vector<const Technique*>& techniques) {
    for (const Technique* t : techniques)
        if (t->needsReceiverBounds()) {
            glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
            glEnable(GL_DEPTH_TEST);
            glDepthMask(GL_TRUE);
            return camera.receiverBounds();
        }
    return std::nullopt;
}

std::vector<FrameLight> setUpLights(const GpuScene& gpu, const CameraPass& camera,
                                    const Technique& technique,
                                    const std::optional<Bounds3d>& lsReceivers, SetUpShares& shared,
                                    const RasterOptions& options) {
    static const std::optional<Bounds3d> notAsked;
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    // The depth probe is a diagnostic, no part of the technique's work: not in the counted frame.
    const bool probe = !countingBuildActive();
    std::vector<FrameLight> lights;
    // The resolves hold their light's target: no element moves once made.
    lights.reserve(gpu.scene().lights.size());
    for (const Light& light : gpu.scene().lights) {
        lights.push_back({&light, LightTarget(camera, probe && technique.probesDepth()),
                          technique.setUp({light, gpu, camera,
                                           technique.needsReceiverBounds() ? lsReceivers : notAsked,
                                           &shared, probe, options.frameIndex, options.temporal})});
        if (const Resolve* resolve = technique.resolve())
            lights.back().resolve = resolve->setUp(
                {light, gpu, camera, lights.back().target, options.temporal, &technique});
    }
    return lights;
}

// One frame of the technique's counting build (docs/metrics.md, "Work"), before its timed
// instance is set up: an instance of its own, so that the timed frames run the very programs they
// ran before counting existed. What its set-up leaves in `shared` (a bake made by ordinary
// programs) the timed instance takes over. Its work by "<light>.<pass>" and "camera".
std::map<std::string, PassWork> countWork(const GpuScene& gpu, const CameraPass& camera,
                                          const Technique& technique,
                                          const std::optional<Bounds3d>& lsReceivers,
                                          SetUpShares& shared, const RasterOptions& options,
                                          const GlContext& gl) {
    std::vector<FrameLight> lights;
    {
        const CountingBuild counting;
        lights = setUpLights(gpu, camera, technique, lsReceivers, shared, options);
    }
    gl.throwIfError("technique " + technique.name() + ", counting build set-up");
    WorkCounter counter;
    renderFrame(camera, lights, counter, true);
    gl.throwIfError("technique " + technique.name() + ", counted frame");
    return counter.byPass();
}

// One technique's lights, timers and wall times while its group renders, and its counted work.
struct TechniqueFrames {
    size_t index;
    const Technique* technique;
    std::vector<FrameLight> lights;
    PassTimer timer;
    std::vector<double> wallMs;
    uint64_t memoryBytes = 0;
    std::map<std::string, PassWork> work;  // empty when not counted
};

// The counted work of one light (its passes by name, and their sum), of the camera pass and of
// the frame.
void addWork(const TechniqueFrames& t, RasterStats& s) {
    if (t.work.empty()) return;
    const auto find = [&](const std::string& key) {
        const auto it = t.work.find(key);
        return it == t.work.end() ? PassWork{} : it->second;
    };
    s.cameraWork = find("camera");
    s.frameWork = s.cameraWork;
    for (RasterLightStats& ls : s.lights) {
        ls.work = PassWork{};
        for (const std::string& pass : ls.passes) {
            ls.workByPass[pass] = find(ls.name + "." + pass);
            *ls.work += ls.workByPass[pass];
        }
        *s.frameWork += *ls.work;
    }
}

RasterStats collectStats(const TechniqueFrames& t, const CameraPass& camera,
                         const RasterOptions& options, const GlContext& gl, int interleavedWith) {
    RasterStats s;
    s.technique = t.technique->name();
    s.parameters = t.technique->values().settings();
    s.width = camera.width();
    s.height = camera.height();
    s.gl = {gl.renderer(), gl.version(), gl.platform()};
    for (const FrameLight& l : t.lights) {
        RasterLightStats ls = l.passes->describe();
        ls.name = l.light->name;
        ls.type = lightTypeName(l.light->type);
        ls.family = findTechnique(t.technique->name()).family;
        ls.passes = l.passes->passNames();
        ls.memoryBytes = l.passes->memoryBytes() +
                         uint64_t(camera.width()) * uint64_t(camera.height()) * 8;  // V, aliasing
        if (l.resolve) {
            for (const std::string& pass : t.technique->resolve()->passNames())
                ls.passes.push_back(pass);
            ls.memoryBytes += l.resolve->memoryBytes();
            s.historyFrames = l.resolve->historyFrames();
        }
        for (const std::string& pass : ls.passes)
            ls.passMs[pass] = t.timer.stats(l.light->name + "." + pass);
        s.lights.push_back(std::move(ls));
    }
    s.timings = {options.frames, options.warmup, t.timer.stats("camera"), timingStats(t.wallMs),
                 interleavedWith};
    addWork(t, s);
    return s;
}

// The depth comparison's channels of one light (docs/exr-channels.md), lengths in world units: the
// local frame only scales by a power of two, so each value is exact and the order of the depths,
// what the shader compared, is kept.
void addDepthComparison(const DepthComparison& c, const std::string& light, const LocalFrame& frame,
                        ChannelImage& image) {
    namespace ch = channels;
    float* planes[3] = {image.addChannel(ch::lightChannel(light, ch::kMapDepth)),
                        image.addChannel(ch::lightChannel(light, ch::kReceiverDepth)),
                        image.addChannel(ch::lightChannel(light, ch::kMapTexel))};
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        const bool compared = c.probe[4 * i + 2] > 0.0f;  // else -1, -1, 0 as they are
        for (size_t k = 0; k < 3; ++k)
            planes[k][i] =
                compared ? float(frame.wsLength(c.probe[4 * i + k])) : c.probe[4 * i + k];
    }
    if (!c.unfilteredVisibility.empty())
        std::copy(c.unfilteredVisibility.begin(), c.unfilteredVisibility.end(),
                  image.addChannel(ch::lightChannel(light, ch::kVisibilityUnfiltered)));
}

RasterResult readResult(const TechniqueFrames& t, const ChannelImage& geometry,
                        const LocalFrame& frame) {
    RasterResult result;
    result.image = geometry;
    for (const FrameLight& l : t.lights) {
        namespace ch = channels;
        const std::vector<float> vis = l.target.readVisibility(), alias = l.target.readAliasing();
        std::copy(vis.begin(), vis.end(),
                  result.image.addChannel(ch::lightChannel(l.light->name, ch::kVisibility)));
        std::copy(alias.begin(), alias.end(),
                  result.image.addChannel(ch::lightChannel(l.light->name, ch::kPredictedAliasing)));
        if (const std::optional<DepthComparison> c = l.passes->readDepthComparison(l.target))
            addDepthComparison(*c, l.light->name, frame, result.image);
    }
    return result;
}

// Records nothing: the probed frame is neither timed nor counted.
class NoRecorder final : public PassRecorder {
  public:
    void begin(const std::string&) override {}
    void end() override {}
};

// One more frame of a technique whose lights can say what their depth comparison saw, with the
// probe on (docs/exr-channels.md): after the timed frames, so it costs them nothing. It renders
// V again with the probe's program, the same V bit for bit (checked on the shipped scenes).
void renderProbedFrame(const CameraPass& camera, TechniqueFrames& t, const GlContext& gl) {
    bool any = false;
    for (FrameLight& l : t.lights)
        if (l.passes->probeDepth(true)) {
            l.target.setProbing(true);
            any = true;
        }
    if (!any) return;
    NoRecorder none;
    renderFrame(camera, t.lights, none);
    gl.throwIfError("technique " + t.technique->name() + ", probed frame");
    for (FrameLight& l : t.lights) {
        l.passes->probeDepth(false);
        l.target.setProbing(false);
    }
}

// Renders the group's frames, technique after technique within each frame, then each one's probed
// frame, and hands each result over.
void renderGroup(const CameraPass& camera, const LocalFrame& localFrame,
                 std::vector<TechniqueFrames>& group, const RasterOptions& options,
                 const GlContext& gl, const InterleavedCallbacks& callbacks) {
    if (group.empty()) return;
    std::vector<size_t> indices;
    for (const TechniqueFrames& t : group) indices.push_back(t.index);
    if (callbacks.groupStarts) callbacks.groupStarts(indices);
    for (int frame = 0; frame < options.warmup + options.frames; ++frame)
        for (TechniqueFrames& t : group) {
            const double ms = renderFrame(camera, t.lights, t.timer);
            // Each technique's frame is checked: the error is thrown while it is known whose.
            gl.throwIfError("technique " + t.technique->name() + ", frame " +
                            std::to_string(frame));
            t.timer.endFrame(frame >= options.warmup);
            if (frame >= options.warmup) t.wallMs.push_back(ms);
        }
    for (TechniqueFrames& t : group) {
        renderProbedFrame(camera, t, gl);
        // What the next frame's resolves read (the caller's temporal state).
        for (FrameLight& l : t.lights)
            if (l.resolve) l.resolve->keep();
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    // Every technique's camera pass drew the same surfaces: one readback serves all.
    ChannelImage geometry(camera.width(), camera.height());
    camera.readGeometry(geometry);
    for (TechniqueFrames& t : group) {
        RasterResult r = readResult(t, geometry, localFrame);
        r.stats = collectStats(t, camera, options, gl, int(group.size()));
        gl.throwIfError("technique " + t.technique->name() + ", read back");
        if (callbacks.done) callbacks.done(t.index, std::move(r));
    }
    group.clear();
}

// Renders the techniques `indices` of the list with one camera pass.
void renderWithCamera(const GpuScene& gpu, const CameraPass& camera,
                      const std::vector<const Technique*>& techniques,
                      const std::vector<size_t>& indices, const RasterOptions& options,
                      const GlContext& gl, const InterleavedCallbacks& callbacks) {
    const std::optional<Bounds3d> lsReceivers = receiverBounds(camera, techniques);
    std::vector<TechniqueFrames> group;
    uint64_t groupBytes = 0;
    for (const size_t i : indices) {
        std::map<std::string, PassWork> work;
        SetUpShares shared;  // the counted instance's set-up, for the timed one
        if (options.countWork)
            work = countWork(gpu, camera, *techniques[i], lsReceivers, shared, options, gl);
        TechniqueFrames t{i,
                          techniques[i],
                          setUpLights(gpu, camera, *techniques[i], lsReceivers, shared, options),
                          {},
                          {},
                          0,
                          std::move(work)};
        // The scene's upload and camera pass (first technique), then this technique's set-up.
        gl.throwIfError("technique " + techniques[i]->name() + ", set-up");
        for (const FrameLight& l : t.lights)
            t.memoryBytes += l.passes->memoryBytes() + (l.resolve ? l.resolve->memoryBytes() : 0);
        // A full group renders first; this technique's objects exist already and start the next.
        if (!group.empty() && groupBytes + t.memoryBytes > options.interleaveBudgetBytes) {
            renderGroup(camera, gpu.frame(), group, options, gl, callbacks);
            groupBytes = 0;
        }
        groupBytes += t.memoryBytes;
        group.push_back(std::move(t));
    }
    renderGroup(camera, gpu.frame(), group, options, gl, callbacks);
}

// A technique's camera jitter in this frame, in pixels: its resolve's (a TAA's), else none.
glm::dvec2 jitterOf(const Technique& technique, int frameIndex) {
    const Resolve* resolve = technique.resolve();
    return resolve ? resolve->jitterPixels(frameIndex) : glm::dvec2(0.0);
}

}  // namespace

void renderInterleaved(const Scene& scene, const std::vector<const Technique*>& techniques,
                       const RasterOptions& options, const GlContext& gl,
                       const InterleavedCallbacks& callbacks) {
    CameraDesc camDesc = options.camera.value_or(scene.camera);
    if (options.width > 0) camDesc.width = options.width;
    if (options.height > 0) camDesc.height = options.height;
    GpuScene gpu(scene);
    gpu.bind();
    // Techniques whose camera is jittered (a TAA's) render with a camera pass of their jitter;
    // the others, in the list's order, with the unjittered one.
    std::vector<std::pair<glm::dvec2, std::vector<size_t>>> byJitter;
    for (size_t i = 0; i < techniques.size(); ++i) {
        const glm::dvec2 jitter = jitterOf(*techniques[i], options.frameIndex);
        size_t k = 0;
        while (k < byJitter.size() && byJitter[k].first != jitter) ++k;
        if (k == byJitter.size()) byJitter.push_back({jitter, {}});
        byJitter[k].second.push_back(i);
    }
    for (const auto& [jitter, indices] : byJitter) {
        const CameraPass camera(gpu, camDesc, jitter);
        renderWithCamera(gpu, camera, techniques, indices, options, gl, callbacks);
    }
}

RasterResult renderRaster(const Scene& scene, const Technique& technique,
                          const RasterOptions& options, const GlContext& gl) {
    RasterResult result;
    renderInterleaved(scene, {&technique}, options, gl,
                      {nullptr, [&](size_t, RasterResult&& r) { result = std::move(r); }});
    return result;
}

RasterResult renderConverged(const Scene& scene, const Technique& technique,
                             const RasterOptions& options, const GlContext& gl) {
    if (options.converge <= 1) return renderRaster(scene, technique, options, gl);
    TemporalState state;
    RasterResult result;
    for (int f = 0; f < options.converge; ++f) {
        state.beginFrame(f);
        RasterOptions o = options;
        o.frameIndex = f;
        o.temporal = &state;
        if (f + 1 < options.converge) o.frames = 1, o.warmup = 0, o.countWork = false;
        result = renderRaster(scene, technique, o, gl);
    }
    return result;
}

}  // namespace so
