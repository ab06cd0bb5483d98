// A percentile by the nearest-rank rule (the smallest value with at least q of the sample at or
// below it): always a measured value. 0 for an empty sample.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace so {

inline double nearestRankPercentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t k =
        std::min(v.size() - 1, size_t(std::ceil(q * double(v.size()))) - (q > 0 ? 1 : 0));
    return v[k];
}

}  // namespace so
