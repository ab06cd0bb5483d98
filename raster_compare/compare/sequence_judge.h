// Adds up a sequence's frames, in order, into one technique's and light's SequenceMetrics
// (docs/metrics.md#sequence): mae per frame as computeLightMetrics counts it, the flicker between
// consecutive frames through the known motion (compareFramePair), lag_mae's pixels, and the
// ghosting class on the pixels whose truth just changed (MetricOptions::truthChanged).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "raster_compare/compare/metrics.h"
#include "raster_compare/compare/sequence_metrics.h"

namespace so {

// One frame of a sequence as SequenceJudge takes it: the frame's images and camera, and the motion
// of the meshes since the frame before (none for the first frame, or when nothing moves).
struct SequenceFrame {
    TemporalFrame frame;
    const MeshMotions* motion = nullptr;
};

// One technique and light over a sequence's frames, given in order. Keeps the previous frame's
// images by pointer (the caller keeps them alive until the next frame is added) and the oracle's
// V of the last kLagFrames frames.
class SequenceJudge {
  public:
    SequenceJudge(std::string light, MetricOptions options);
    // Measures the frame: its mae, its flicker against the frame before, its lag pixels, its
    // ghosting; keeps its truth-changed mask (SequenceMetrics::lastTruthChanged).
    void add(const SequenceFrame& frame);
    const SequenceMetrics& metrics() const { return metrics_; }

  private:
    // 1 where `now` (the truth's V, NaN where it missed) differs by more than kLagJump from one of
    // the kLagFrames frames before.
    std::vector<uint8_t> truthChanged(const std::vector<float>& now) const;
    std::string light_;
    MetricOptions options_;
    SequenceMetrics metrics_;
    std::optional<TemporalFrame> previous_;
    // The oracle's V (NaN where it missed) of the frames before, most recent last.
    std::vector<std::vector<float>> oracleHistory_;
};

}  // namespace so
