#include "raster_compare/pipeline/sequence_compare.h"

#include <algorithm>
#include <array>
#include <memory>
#include <optional>

#include "core/channels.h"
#include "core/error.h"
#include "core/scene_pose.h"
#include "raster_compare/compare/sequence_judge.h"
#include "raster_compare/gl/time/temporal_state.h"
#include "raster_compare/pipeline/frame_images.h"

namespace so {

namespace {

// One frame's images and time; two of them alternate, so that the judges' pointers to the frame
// before stay valid while the next is made.
struct SequenceFrameImages : FrameImages {
    double t = 0.0;
};

// Where each mesh's points of frame t were at tPrev.
MeshMotions motionSince(const Scene& scene, double t, double tPrev) {
    MeshMotions motion(scene.meshes.size());
    for (size_t m = 0; m < motion.size(); ++m) motion[m] = meshMotion(scene, m, t, tPrev);
    return motion;
}

}  // namespace

SequenceResult measureSequence(const Scene& scene, const std::vector<const Technique*>& techniques,
                               const OracleOptions& oracle, const OracleCacheOptions& cache,
                               const RasterOptions& raster, const MetricOptions& metricOptions,
                               const GlContext& gl, const ProgressCallback& progressCallback,
                               const ChannelImage* lastOracle) {
    if (!scene.sequence)
        throwInputError(scene.path.string(), "sequence",
                        "missing: judging a sequence needs one (scene_format 5, "
                        "docs/scene-format.md)");
    const Sequence& sequence = *scene.sequence;
    SequenceResult out;
    out.frames = sequence.frames;
    // Per technique and light: its judge.
    std::vector<std::vector<SequenceJudge>> judges(techniques.size());
    for (size_t k = 0; k < techniques.size(); ++k) {
        MetricOptions m = metricOptions;
        m.filteredTechnique = techniques[k]->filtered();
        m.comparesDepth = familyComparesDepth(findTechnique(techniques[k]->name()).family);
        for (const Light& light : scene.lights) judges[k].emplace_back(light.name, m);
    }
    // What every technique builds over the frames: its resolves' and denoisers' histories, on the
    // GPU inside each frame's render (timed and counted there).
    TemporalState temporal;
    std::array<SequenceFrameImages, 2> slots;
    Progress progress("sequence frames", uint64_t(sequence.frames), progressCallback);
    for (int f = 0; f < sequence.frames; ++f) {
        SequenceFrameImages& frame = slots[size_t(f) % 2];
        frame.t = sequenceTime(sequence, f);
        const std::optional<MeshMotions> motion =
            f > 0 ? std::optional(motionSince(scene, frame.t, slots[size_t(f + 1) % 2].t))
                  : std::nullopt;
        temporal.beginFrame(f, motion ? *motion : MeshMotions{});
        // The posed scene's camera is the frame's (its camera_path moved it): no other camera.
        OracleOptions o = oracle;
        o.camera.reset();
        RasterOptions r = raster;
        r.camera.reset();
        r.frameIndex = f;
        r.temporal = &temporal;
        static_cast<FrameImages&>(frame) = renderFrameImages(
            sceneAtTime(scene, frame.t), techniques, o, cache, r, gl, out.warnings,
            f == sequence.frames - 1 ? lastOracle : nullptr, f == sequence.frames - 1);
        for (size_t k = 0; k < techniques.size(); ++k)
            for (size_t li = 0; li < scene.lights.size(); ++li)
                judges[k][li].add({{frame.camera, &frame.oracle, &frame.rasters[k]},
                                   motion ? &*motion : nullptr});
        progress.advance(1);
    }
    SequenceFrameImages& last = slots[size_t(sequence.frames - 1) % 2];
    out.metrics.resize(techniques.size());
    for (size_t k = 0; k < techniques.size(); ++k) {
        for (const SequenceJudge& judge : judges[k]) out.metrics[k].push_back(judge.metrics());
        out.lastImages.push_back(std::move(last.rasters[k]));
        out.lastStats.push_back(std::move(last.stats[k]));
    }
    return out;
}

}  // namespace so
