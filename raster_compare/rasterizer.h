// The raster path's render: per light a shadow map (2D or cube), one camera pass for what each
// pixel sees, and per light a visibility pass with the chosen technique; every pass timed with GL
// timer queries over several frames after a warm-up. Same scene model and camera as the oracle:
// pixel (x, y) here is the oracle's pixel (x, y).
#pragma once

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "raster_compare/technique.h"

namespace so {

class GlContext;

struct RasterOptions {
    int width = 0, height = 0;  // 0: the scene camera's
    int frames = 5;             // timed frames (median reported)
    int warmup = 1;             // untimed frames first
};

struct RasterResult {
    ChannelImage image;    // A, P.*, N.*, Z, id.mesh, id.prim, NAME.V (docs/exr-channels.md)
    nlohmann::json stats;  // technique, parameters, light cameras, renderer, timings
};

RasterResult renderRaster(const Scene& scene, const ShadowTechnique& technique,
                          const ParamValues& params, const RasterOptions& options,
                          const GlContext& gl);

}  // namespace so
