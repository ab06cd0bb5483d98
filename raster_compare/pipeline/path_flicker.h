// Temporal flicker (compare --frames-path N): the scene's camera path (scene_format 2) rendered in
// N frames, the oracle and every technique once per frame, measured for temporal flicker
// (temporal.h, docs/metrics.md#temporal-flicker). The frames are a sequence whose only motion is
// the camera's: each is rendered with its index and one temporal state, so that what a technique
// resolves over frames (its `resolve`, a denoiser's history) builds along the path as in
// compare --sequence. A comparison's other metrics stay on the scene camera.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "oracle/oracle_cache.h"
#include "raster_compare/compare/report.h"
#include "raster_compare/compare/temporal.h"
#include "raster_compare/gl/render/renderer.h"

namespace so {

class GlContext;

struct PathFlicker {
    int frames = 0;
    std::vector<std::vector<TemporalFlicker>> flicker;  // [technique][light]
    std::vector<std::optional<FlickerStrip>> strips;    // [light]: the worst technique's worst pair
    std::vector<std::string> warnings;  // the frames' oracle cache's (CachedOracle::warnings)
};

// Throws InputError (the scene file, camera_path) when the scene has no camera path.
// `labels`: the techniques' labels, for the strips. `progress` counts frames ("camera path
// frames") and can cancel.
PathFlicker measurePathFlicker(const Scene& scene, const std::vector<const Technique*>& techniques,
                               const std::vector<std::string>& labels, const OracleOptions& oracle,
                               const OracleCacheOptions& cache, const RasterOptions& raster,
                               const GlContext& gl, int frames,
                               const ProgressCallback& progress = {});

}  // namespace so
