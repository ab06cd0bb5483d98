// Small helpers shared by the benchmarks: timing and medians.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace so::bench {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Seconds one call of f takes.
template <class F>
double timeOnce(F&& f) {
    const auto t0 = Clock::now();
    f();
    return secondsSince(t0);
}

}  // namespace so::bench
