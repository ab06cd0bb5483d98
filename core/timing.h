// A time measured over repeated frames: median and quartiles, so that a reader sees the spread
// beside the figure (docs/techniques.md, Timing).
#pragma once

#include <vector>

namespace so {

struct TimingStats {
    double median = 0.0, p25 = 0.0, p75 = 0.0;  // ms
    // The interquartile range is above 20% of the median: the figure is noise-prone.
    bool noisy() const { return p75 - p25 > 0.2 * median; }
};

// Passes run one after the other: medians and quartiles added (the quartiles of a sum are not the
// sum of quartiles; this bounds its spread from above).
inline TimingStats& operator+=(TimingStats& a, const TimingStats& b) {
    a.median += b.median;
    a.p25 += b.p25;
    a.p75 += b.p75;
    return a;
}

// Median and quartiles of a sample by the nearest-rank rule: each is a measured value.
TimingStats timingStats(std::vector<double> ms);

}  // namespace so
