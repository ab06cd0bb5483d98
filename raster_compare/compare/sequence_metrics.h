// compare --sequence's metrics of one technique and light (docs/metrics.md#sequence): the error at
// every frame of the scene's sequence against that frame's oracle, the flicker the truth does not
// make (tracked through the known motion, temporal.h) and the error where the truth has just
// changed (lag and ghosting). Typed; JSON at the edge (metrics.json's "sequence"). SequenceJudge
// (sequence_judge.h) adds the frames up.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/compare/temporal.h"

namespace so {

// lag_mae's pixels: counted pixels whose oracle V differs by more than kLagJump from the oracle's
// V at the same pixel in one of the kLagFrames frames before.
inline constexpr double kLagJump = 0.5;
inline constexpr int kLagFrames = 4;
// flicker_rate's change of the technique's V (TemporalOptions::rasterJump): a tenth of the light,
// where temporal_flicker_rate asks for a flip (0.5). The error of rotated taps is grey-level noise
// that changes V by fractions from frame to frame, seldom across 0.5: measured on the still box of
// tests/pipeline/sequence_compare_test.cpp, pcf's jittered taps (history=0) change 1154 tracked
// pairs by more than 0.1 and none by more than 0.5.
inline constexpr double kSequenceFlickerJump = 0.1;

struct SequenceMetrics {
    std::vector<double> maePerFrame;  // mae (docs/metrics.md) of each frame, in order
    TemporalFlicker flicker;          // consecutive frames, tracked through the known motion
    size_t lagPixels = 0;             // counted pixel-frames whose truth just changed
    double lagAbsSum = 0.0;           // their error (ErrorMaps::error) summed
    // Of those pixel-frames, the ones more than r (boundary_radius) from the frame's oracle
    // boundary and outside its penumbra, and those of them that are wrong: ghosting
    // (LightMetrics::ghostingPixels).
    size_t ghostingEligible = 0, ghostingPixels = 0;
    // The last frame's mask of pixels whose truth changed within the kLagFrames frames before it
    // (MetricOptions::truthChanged): the row's own metrics of the last frame class its ghosting
    // with it. Not in the JSON.
    std::vector<uint8_t> lastTruthChanged;
    int frames() const { return int(maePerFrame.size()); }
    double maeMean() const;                // 0 without frames
    double maeLast() const;                // 0 without frames
    std::optional<double> lagMae() const;  // none where no pixel's truth changed
    // ghostingPixels / ghostingEligible; none where no pixel's truth changed away from an edge
    std::optional<double> ghostingRate() const;
    // {"frames", "mae_per_frame", "mae_mean", "mae_last", "flicker_rate", "tracked_pairs",
    //  "flickering_pairs", "lag_mae", "lag_pixels", "ghosting_rate", "ghosting_pixels"}
    nlohmann::json toJson() const;
};

}  // namespace so
