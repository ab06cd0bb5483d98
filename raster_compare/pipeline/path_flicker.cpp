#include "raster_compare/pipeline/path_flicker.h"

#include "core/camera_path.h"
#include "core/channels.h"
#include "core/error.h"
#include "raster_compare/gl/time/temporal_state.h"
#include "raster_compare/pipeline/frame_images.h"

namespace so {

namespace ch = channels;

namespace {

// One frame's images, kept until the next frame is measured against it.
using PathFrame = FrameImages;

std::vector<float> plane(const ChannelImage& image, const std::string& light) {
    const float* v = image.channel(ch::lightChannel(light, ch::kVisibility));
    return std::vector<float>(v, v + image.pixelCount());
}

// The worst pair so far of one technique and light, with what its strip needs.
struct WorstPair {
    size_t flickering = 0;
    std::optional<FlickerStrip> strip;
};

// Frame f of the path: a sequence whose only motion is the camera's, so the techniques that
// resolve their frames over time do it through `temporal` as in compare --sequence.
PathFrame renderFrame(const Scene& scene, const std::vector<const Technique*>& techniques,
                      const OracleOptions& oracle, const OracleCacheOptions& cache,
                      const RasterOptions& raster, const GlContext& gl, const CameraDesc& pose,
                      int f, TemporalState& temporal, std::vector<std::string>& warnings) {
    OracleOptions o = oracle;
    o.camera = pose;
    RasterOptions r = raster;
    r.camera = pose;
    r.frameIndex = f;
    r.temporal = &temporal;
    temporal.beginFrame(f);
    return renderFrameImages(scene, techniques, o, cache, r, gl, warnings);
}

void measurePair(const PathFrame& prev, const PathFrame& next, const Scene& scene,
                 const std::vector<std::string>& labels, int pairIndex, PathFlicker& out,
                 std::vector<std::vector<WorstPair>>& worst) {
    for (size_t t = 0; t < labels.size(); ++t)
        for (size_t li = 0; li < scene.lights.size(); ++li) {
            const std::string& light = scene.lights[li].name;
            std::vector<uint8_t> mask;
            const FramePairFlicker p =
                compareFramePair({prev.camera, &prev.oracle, &prev.rasters[t]},
                                 {next.camera, &next.oracle, &next.rasters[t]}, light, {}, &mask);
            out.flicker[t][li].add(p);
            WorstPair& w = worst[t][li];
            if (w.strip && p.flickering <= w.flickering) continue;
            w.flickering = p.flickering;
            w.strip = FlickerStrip{labels[t],
                                   pairIndex,
                                   0.0,
                                   p.flickering,
                                   next.oracle.width(),
                                   next.oracle.height(),
                                   plane(prev.rasters[t], light),
                                   plane(next.rasters[t], light),
                                   plane(next.oracle, light),
                                   std::move(mask)};
        }
}

}  // namespace

PathFlicker measurePathFlicker(const Scene& scene, const std::vector<const Technique*>& techniques,
                               const std::vector<std::string>& labels, const OracleOptions& oracle,
                               const OracleCacheOptions& cache, const RasterOptions& raster,
                               const GlContext& gl, int frames,
                               const ProgressCallback& progressCallback) {
    if (!scene.cameraPath)
        throwInputError(scene.path.string(), "camera_path",
                        "missing: frames along the camera path need one (scene_format 2, "
                        "docs/scene-format.md)");
    const std::vector<CameraDesc> poses = sampleCameraPath(*scene.cameraPath, scene.camera, frames);
    PathFlicker out;
    out.frames = frames;
    out.flicker.assign(techniques.size(), std::vector<TemporalFlicker>(scene.lights.size()));
    std::vector<std::vector<WorstPair>> worst(techniques.size(),
                                              std::vector<WorstPair>(scene.lights.size()));
    PathFrame prev;
    TemporalState temporal;
    Progress progress("camera path frames", uint64_t(frames), progressCallback);
    for (int f = 0; f < frames; ++f) {
        PathFrame next = renderFrame(scene, techniques, oracle, cache, raster, gl, poses[size_t(f)],
                                     f, temporal, out.warnings);
        if (f > 0) measurePair(prev, next, scene, labels, f - 1, out, worst);
        prev = std::move(next);
        progress.advance(1);
    }
    // Per light, the strip of the technique with the highest rate.
    out.strips.resize(scene.lights.size());
    for (size_t li = 0; li < scene.lights.size(); ++li) {
        size_t best = 0;
        double bestRate = -1.0;
        for (size_t t = 0; t < techniques.size(); ++t) {
            const double r = out.flicker[t][li].rate().value_or(0.0);
            if (r > bestRate) best = t, bestRate = r;
        }
        if (techniques.empty() || !worst[best][li].strip) continue;
        out.strips[li] = std::move(worst[best][li].strip);
        out.strips[li]->rate = bestRate;
    }
    return out;
}

}  // namespace so
