// Work a pass does in one frame, counted exactly (docs/metrics.md, "Work"): what a GPU's time
// follows, beside the milliseconds of whatever renderer measured them (llvmpipe, a CPU
// rasterizer, here). The raster path counts it (raster_compare/gl/context/work_counter.h);
// metrics.json carries it per light under cost.work, raster.json per pass.
#pragma once

#include <cstdint>

namespace so {

struct WorkCounts {
    // Fragment shader invocations, with the depth and stencil tests before the shader wherever it
    // cannot discard (a GPU's early tests): the visibility pass shades the pixels it lights.
    uint64_t fragments = 0;
    uint64_t textureTaps = 0;    // texture lookups the shaders make (a filtered one is one tap)
    uint64_t texelsWritten = 0;  // render-target texels the pass writes, each once per pass
    // The render targets' bytes written and read (each texel once per pass), and the bytes of
    // the texels every tap fetches (no texture cache).
    uint64_t bytesMoved = 0;
    uint64_t drawCalls = 0;
    uint64_t passes = 0;  // passes run (a pass run per sample counts per sample)
    // Shadow rays traced (the raytraced family's, the work RT cores do on a GPU); 0 elsewhere.
    uint64_t raysTraced = 0;

    WorkCounts& operator+=(const WorkCounts& o) {
        fragments += o.fragments;
        textureTaps += o.textureTaps;
        texelsWritten += o.texelsWritten;
        bytesMoved += o.bytesMoved;
        drawCalls += o.drawCalls;
        passes += o.passes;
        raysTraced += o.raysTraced;
        return *this;
    }
    bool operator==(const WorkCounts&) const = default;
};

}  // namespace so
