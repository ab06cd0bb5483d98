// The raster path's render: the scene on the GPU, the camera pass, and per light the technique's
// own passes writing that light's V into the shared frame; every pass timed with GL timer queries
// over several frames after a warm-up. Same scene model and camera as the oracle: pixel (x, y)
// here is the oracle's pixel (x, y).
#pragma once

#include "core/scene.h"
#include "raster_compare/gl/raster_result.h"
#include "raster_compare/gl/technique.h"

namespace so {

class GlContext;

struct RasterOptions {
    int width = 0, height = 0;  // 0: the scene camera's
    int frames = 5;             // timed frames (median reported)
    int warmup = 1;             // untimed frames first
};

RasterResult renderRaster(const Scene& scene, const Technique& technique,
                          const RasterOptions& options, const GlContext& gl);

}  // namespace so
