// The stats of `trace --tile`'s bands merged into the whole image's (trace-merge, trace_merge.h;
// docs/oracle.md, "Tiles"): beside their one caller rather than in oracle_stats.h, which writes and
// reads one run's.
#pragma once

#include <cstdint>
#include <vector>

#include "oracle/oracle_stats.h"

namespace so {

// One band's stats (`trace --tile`) and what merging needs beyond them.
struct TileStats {
    OracleStats stats;
    // Per light, in scene order: the pixels of a sampled light whose V ended strictly between 0
    // and 1 (the penumbra the cost curve's penumbra mean averages over); 0 for other lights.
    std::vector<uint64_t> penumbraPixels;
};

// The whole image's stats from its bands' (trace-merge; docs/oracle.md, "Tiles"): counts,
// samples, rays and seconds are sums, maxima are maxima, means are re-weighted by what they
// average over, and the setup (effects, seed, frame, libraries) is the first band's. The bands
// must come from the same scene and options, in any order. uniformSpp is the bands' largest: only
// the per-pixel variances give the whole image's (the caller recomputes it from the image). No
// bands, or bands whose lights differ, are std::invalid_argument.
OracleStats mergeTileStats(const std::vector<TileStats>& tiles, int width, int height);

}  // namespace so
