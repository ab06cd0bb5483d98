// The penumbra width error (docs/metrics.md): how much wider or narrower a technique's soft edge
// is than the oracle's, in pixels, measured along the oracle's gradient through its mid contour.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace so {

struct PenumbraWidthError {
    double mean = 0.0, p95 = 0.0;  // of |width_technique - width_oracle| over the profiles, px
    double oracleMeanWidth = 0.0;  // the oracle's own mean 10%-90% width, px (for scale)
    size_t profiles = 0;
};

// Vo, Vr: the oracle's and the technique's V (row-major w x h); `counted`: the pixels both see
// alike (metrics.h). From every counted pixel where the oracle's V crosses 0.5 towards a counted
// 4-neighbour, a line along the oracle's gradient, sampled every quarter pixel to 128 pixels each
// way; the 10%-90% width of a profile is the length of the line where 0.1 < V < 0.9. A line that
// leaves the counted pixels before both profiles have left their transition is dropped. None
// without a profile.
std::optional<PenumbraWidthError> penumbraWidthError(int w, int h, const float* Vo, const float* Vr,
                                                     const std::vector<uint8_t>& counted);

}  // namespace so
