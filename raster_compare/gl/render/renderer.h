// The raster path's render: the scene on the GPU, the camera pass, and per light the technique's
// own passes writing that light's V into the shared frame; every pass timed with GL timer queries
// over several frames after a warm-up. Same scene model and camera as the oracle: pixel (x, y)
// here is the oracle's pixel (x, y).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/raster_option_table.h"
#include "core/scene.h"
#include "raster_compare/gl/render/raster_result.h"
#include "raster_compare/gl/technique.h"

namespace so {

class GlContext;
class TemporalState;

struct RasterOptions {
    int width = 0, height = 0;  // 0: the scene camera's
    // Another camera than the scene's (a frame of compare --frames-path); width and height above
    // still override its size.
    std::optional<CameraDesc> camera;
    // The frame's index in the caller's frames (compare --sequence, --converge): techniques with
    // temporal=on rotate their taps by it (docs/techniques.md#temporal) and a TAA jitters the
    // camera by it; 0 for a single frame.
    int frameIndex = 0;
    // The caller's temporal state (time/temporal_state.h), begun for frameIndex: what the frame
    // before left for every resolve and denoiser, and where this frame's is kept. Null: a cold
    // start (history_frames 0).
    TemporalState* temporal = nullptr;
    int frames = kDefaultFrames;  // timed frames (median and quartiles reported)
    int warmup = kDefaultWarmup;  // untimed frames first
    // renderConverged (raster --converge, the compare option table's row): still frames rendered in
    // order with one temporal state, the last returned; 0 or 1: a single frame.
    int converge = 1;
    // Before its timed frames, each technique's work is counted in one frame of its counting
    // build (work_counter.h; docs/metrics.md, "Work"), which never runs in the timed frames.
    bool countWork = true;
    // Techniques rendered together take turns frame by frame, so that background load falls on
    // all alike; a group holds at most this much estimated GL memory (the next starts after).
    uint64_t interleaveBudgetBytes = uint64_t(2) << 30;
};

struct InterleavedCallbacks {
    // A group of techniques (indices into the list) is about to be rendered together.
    std::function<void(const std::vector<size_t>&)> groupStarts;
    // A technique's result, as soon as its group is done (its GL objects are freed after).
    std::function<void(size_t, RasterResult&&)> done;
};

// Renders every technique of the list on the scene, in groups whose frames interleave. A GL error
// throws GlError (GlContext::throwIfError) after the technique's set-up or frame that caused it;
// the GL driver's warnings wait in the context for the caller (GlContext::takeWarnings).
void renderInterleaved(const Scene& scene, const std::vector<const Technique*>& techniques,
                       const RasterOptions& options, const GlContext& gl,
                       const InterleavedCallbacks& callbacks);

// One technique alone.
RasterResult renderRaster(const Scene& scene, const Technique& technique,
                          const RasterOptions& options, const GlContext& gl);

// `raster --converge N` and the API's: options.converge still frames (frame index 0 to N - 1) of
// one technique rendered in order with a temporal state of its own, so that what it resolves over
// frames builds; the last frame is the result, timed and counted as `options` says (the frames
// before it one untimed, uncounted frame each). N = 1 is renderRaster: a cold start.
RasterResult renderConverged(const Scene& scene, const Technique& technique,
                             const RasterOptions& options, const GlContext& gl);

}  // namespace so
