// One frame of a comparison that moves (compare --frames-path, compare --sequence): the oracle of
// the frame, traced or read from the oracle cache, and every technique rendered once, untimed
// (only the images matter there: the timed frames and the work are the ordinary comparison's),
// or, for a sequence's last frame, timed and counted as the comparison's options say (what a
// technique builds over frames is only there in the sequence's own last frame).
#pragma once

#include <string>
#include <vector>

#include "oracle/oracle_cache.h"
#include "raster_compare/gl/render/renderer.h"

namespace so {

class GlContext;

struct FrameImages {
    CameraDesc camera;  // the oracle's effective camera for `oracle`'s options
    ChannelImage oracle;
    std::vector<ChannelImage> rasters;  // per technique
    std::vector<RasterStats> stats;     // per technique: its timings and work (`timed` only)
};

// `oracle` and `raster` as the frame wants them (its camera, its frame index); the raster frames
// are set to one untimed frame without a counted one unless `timed`. The oracle cache's warnings
// are appended to `warnings`. `traced`: this frame's oracle for these options, already in hand
// (the ordinary comparison's, for a sequence's last frame), copied instead of traced again.
FrameImages renderFrameImages(const Scene& scene, const std::vector<const Technique*>& techniques,
                              const OracleOptions& oracle, const OracleCacheOptions& cache,
                              RasterOptions raster, const GlContext& gl,
                              std::vector<std::string>& warnings,
                              const ChannelImage* traced = nullptr, bool timed = false);

}  // namespace so
