#include "raster_compare/gl/renderer.h"

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include <epoxy/gl.h>

#include "core/channels.h"
#include "raster_compare/gl/camera_pass.h"
#include "raster_compare/gl/gl_context.h"
#include "raster_compare/gl/gpu_scene.h"
#include "raster_compare/gl/pass_timer.h"

namespace so {

namespace {

// One light in the frame: its target and the technique's passes for it.
struct FrameLight {
    const Light* light;
    LightTarget target;
    std::unique_ptr<LightTechnique> passes;
};

// The frame: every light's own passes, the camera pass, every light's visibility pass. Returns the
// wall time in ms (GL finished).
double renderFrame(const CameraPass& camera, std::vector<FrameLight>& lights, PassTimer& timer) {
    const auto t0 = std::chrono::steady_clock::now();
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    for (FrameLight& l : lights) {
        timer.begin(l.light->name + "." + l.passes->lightPassName());
        l.passes->renderLightPasses();
        timer.end();
    }
    timer.begin("camera");
    camera.render();
    timer.end();
    // The visibility passes shade exactly the surfaces the camera pass found.
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
    for (FrameLight& l : lights) {
        timer.begin(l.light->name + ".visibility");
        l.target.bindAndClear();
        l.passes->renderVisibility();
        timer.end();
    }
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<FrameLight> setUpLights(const GpuScene& gpu, const CameraPass& camera,
                                    const Technique& technique) {
    std::optional<Bounds3d> lsReceivers;
    if (technique.needsReceiverBounds()) {
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        lsReceivers = camera.receiverBounds();
    }
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    std::vector<FrameLight> lights;
    for (const Light& light : gpu.scene().lights)
        lights.push_back(
            {&light, LightTarget(camera), technique.setUp({light, gpu, camera, lsReceivers})});
    return lights;
}

RasterStats collectStats(const Technique& technique, const CameraPass& camera,
                         const std::vector<FrameLight>& lights, const PassTimer& timer,
                         std::vector<double> wallMs, const RasterOptions& options,
                         const GlContext& gl) {
    RasterStats s;
    s.technique = technique.name();
    s.parameters = technique.values().all();
    s.width = camera.width();
    s.height = camera.height();
    s.gl = {gl.renderer(), gl.version(), gl.platform()};
    for (const FrameLight& l : lights) {
        RasterLightStats ls = l.passes->describe();
        for (const std::string& pass : {l.passes->lightPassName(), std::string("visibility")})
            ls.passMs[pass] = timer.medianMs(l.light->name + "." + pass);
        s.lights.push_back(std::move(ls));
    }
    s.timings = {options.frames, options.warmup, timer.medianMs("camera"), median(wallMs)};
    return s;
}

}  // namespace

RasterResult renderRaster(const Scene& scene, const Technique& technique,
                          const RasterOptions& options, const GlContext& gl) {
    CameraDesc camDesc = scene.camera;
    if (options.width > 0) camDesc.width = options.width;
    if (options.height > 0) camDesc.height = options.height;
    GpuScene gpu(scene);
    gpu.bind();
    CameraPass camera(gpu, camDesc);
    std::vector<FrameLight> lights = setUpLights(gpu, camera, technique);

    PassTimer timer;
    std::vector<double> wallMs;
    for (int frame = 0; frame < options.warmup + options.frames; ++frame) {
        const double ms = renderFrame(camera, lights, timer);
        timer.endFrame(frame >= options.warmup);
        if (frame >= options.warmup) wallMs.push_back(ms);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    RasterResult result;
    result.image = ChannelImage(camera.width(), camera.height());
    camera.readGeometry(result.image);
    for (const FrameLight& l : lights) {
        namespace ch = channels;
        const std::vector<float> vis = l.target.readVisibility(), alias = l.target.readAliasing();
        std::copy(vis.begin(), vis.end(),
                  result.image.addChannel(ch::lightChannel(l.light->name, ch::kVisibility)));
        std::copy(alias.begin(), alias.end(),
                  result.image.addChannel(ch::lightChannel(l.light->name, ch::kPredictedAliasing)));
    }
    result.stats = collectStats(technique, camera, lights, timer, wallMs, options, gl);
    return result;
}

}  // namespace so
