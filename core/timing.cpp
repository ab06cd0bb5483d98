#include "core/timing.h"

#include <algorithm>

namespace so {

TimingStats timingStats(std::vector<double> v) {
    if (v.empty()) return {};
    std::sort(v.begin(), v.end());
    auto rank = [&](double q) { return v[std::min(v.size() - 1, size_t(q * double(v.size())))]; };
    return {v[v.size() / 2], rank(0.25), rank(0.75)};
}

}  // namespace so
