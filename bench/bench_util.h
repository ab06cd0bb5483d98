// Small helpers shared by the benchmarks: timing, medians, the near fields.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "embree/embree_handles.h"
#include "oracle/surface_buffer.h"

namespace so::bench {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The processor time this process has used, all threads together.
inline double processCpuSeconds() {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// SO_BENCH_CLOCK=cpu times by the processor time the process used rather than the wall clock:
// on a machine other programs load, time spent waiting for a core then counts for neither side of
// a ratio (docs/benchmarks.md). The figures there are wall-clock times on a quiet machine.
inline bool cpuClock() {
    static const bool cpu = [] {
        const char* v = std::getenv("SO_BENCH_CLOCK");
        return v && std::string(v) == "cpu";
    }();
    return cpu;
}

// Seconds one call of f takes.
template <class F>
double timeOnce(F&& f) {
    if (cpuClock()) {
        const double t0 = processCpuSeconds();
        f();
        return processCpuSeconds() - t0;
    }
    const auto t0 = Clock::now();
    f();
    return secondsSince(t0);
}

// The scaffolding of the plain Embree baselines: items 0 .. n-1 in parallel inside `arena`, each
// task with the float mode Embree asks for and its own intersect context, so that the loops being
// compared differ only in the Embree call `body(ctx, i)` makes.
template <class F>
void forEachWithContext(tbb::task_arena& arena, size_t n, size_t grain, bool coherent, F&& body) {
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                          [&](const tbb::blocked_range<size_t>& r) {
                              setEmbreeFloatMode();
                              RTCIntersectContext ctx;
                              rtcInitIntersectContext(&ctx);
                              if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
                              for (size_t i = r.begin(); i != r.end(); ++i) body(ctx, i);
                          });
    });
}

// The near fields (oracle/near_field.h), built once per image as the oracle builds them after its
// primary pass, unless `skip`: the passes then decide them in double, so their price is in the
// oracle's time. Prints what they took.
inline void buildNearFieldsTimed(tbb::task_arena& arena, const Accel& accel, SurfaceBuffer& sb,
                                 bool skip) {
    const auto t0 = Clock::now();
    if (!skip) arena.execute([&] { buildNearFields(accel, sb); });
    std::printf(
        "near fields: %.1f ms for the image, %llu of %d pixels have one (%zu triangles, %llu "
        "balls shrunk; %llu pixels in %llu tiles unbounded, decided at every hard light)\n",
        1e3 * secondsSince(t0), (unsigned long long)sb.nearFields.pixels, sb.width * sb.height,
        sb.nearFields.ids.size(), (unsigned long long)sb.nearFields.pixelsShrunk,
        (unsigned long long)sb.nearFields.pixelsUnbounded,
        (unsigned long long)sb.nearFields.tilesUnbounded);
}

}  // namespace so::bench
