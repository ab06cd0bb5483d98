// The loop every Embree pass of the oracle runs (primary rays, hard shadows, area shadows), once:
// in parallel over a SurfaceBuffer's rows of 4x4 tiles, as pbrt-v4's ParallelFor2D runs over
// tiles. Each pass writes only its own slots, so the image is the same at any thread count; what a
// pass counts goes into per-thread scratch that the pass sums afterwards (integers: any order).
#pragma once

#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "embree/embree_handles.h"
#include "oracle/accel.h"

namespace so {

// For each chunk of tile rows TBB hands a thread: sets Embree's float mode (its callers' duty, per
// thread), makes the chunk's scratch with makeScratch(), runs body(ty, scratch) for each tile row
// ty in it, then done(scratch, alphaTests) with the alpha tests the chunk's queries ran (counted
// per thread by the alpha filter, accel.h). The body reports its own progress, as often as its
// work per row calls for.
template <typename MakeScratch, typename Body, typename Done>
void forEachTileRow(int tilesY, MakeScratch&& makeScratch, Body&& body, Done&& done) {
    tbb::parallel_for(tbb::blocked_range<int>(0, tilesY, 1),
                      [&](const tbb::blocked_range<int>& rows) {
                          setEmbreeFloatMode();
                          auto scratch = makeScratch();
                          const uint64_t alphaTests0 = Accel::alphaTestsOnThisThread();
                          for (int ty = rows.begin(); ty != rows.end(); ++ty) body(ty, scratch);
                          done(scratch, Accel::alphaTestsOnThisThread() - alphaTests0);
                      });
}

}  // namespace so
