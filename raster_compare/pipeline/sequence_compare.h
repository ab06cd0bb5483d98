// A sequence judged frame by frame (compare --sequence, docs/metrics.md#sequence): for frame k of
// the scene's sequence, at t_k = sequenceTime(k), the scene posed at t_k (core/scene_pose.h), its
// oracle traced or read from the oracle cache (each frame cached on its own, as the camera path's
// frames of path_flicker.h), every technique rendered on it with RasterOptions::frameIndex = k and
// one temporal state for the whole sequence (time/temporal_state.h, with each mesh's motion since
// the frame before), so that what a technique resolves over frames (its resolve, a denoiser's
// history) builds inside each frame's render, on the GPU. The last frame is rendered timed and
// counted: the rows' costs. Each technique and light is judged by a SequenceJudge
// (sequence_judge.h).
#pragma once

#include <string>
#include <vector>

#include "core/progress.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/gl/render/renderer.h"

namespace so {

class GlContext;

struct SequenceResult {
    int frames = 0;
    std::vector<std::vector<SequenceMetrics>> metrics;  // [technique][light]
    // Per technique, the last frame's image as judged (V resolved where the technique has a
    // history): the image the row's ordinary metrics measure (docs/metrics.md#sequence).
    std::vector<ChannelImage> lastImages;
    // Per technique, the last frame's timings and work, rendered with the comparison's raster
    // options and the temporal state of the frames before it: the row's costs.
    std::vector<RasterStats> lastStats;
    std::vector<std::string> warnings;  // the frames' oracle cache's (CachedOracle::warnings)
};

// `scene` has its motion (not a posed frame). Throws InputError (the scene file, sequence) when it
// has no sequence. `metricOptions` as the comparison's (each technique's filtered() is set here).
// `progress` counts frames ("sequence frames") and can cancel. `lastOracle`: the last frame's
// oracle for these options where the caller has it (the ordinary comparison's): not traced twice
// (compare --sequence --no-cache).
SequenceResult measureSequence(const Scene& scene, const std::vector<const Technique*>& techniques,
                               const OracleOptions& oracle, const OracleCacheOptions& cache,
                               const RasterOptions& raster, const MetricOptions& metricOptions,
                               const GlContext& gl, const ProgressCallback& progress = {},
                               const ChannelImage* lastOracle = nullptr);

}  // namespace so
