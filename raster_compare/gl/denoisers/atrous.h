// The a-trous levels (atrous.glsl) that svgf and ffx end with: V and its variance filtered at
// steps 1, 2, 4, ... with SVGF's edge stops on the normal, the depth and V (Schied et al.,
// "Spatiotemporal Variance-Guided Filtering", HPG 2017, section 4.2).
#pragma once

#include "raster_compare/gl/denoisers/ray_frame.h"

namespace so {

class PassClock;

struct EdgeStops {
    double luminance, normal, depth;  // sigma_luminance, sigma_normal, sigma_depth
};

class AtrousFilter {
  public:
    // ffx: FidelityFX's 3 x 3 kernel, its skipped tiles (frame.tiles on unit 5) passed through;
    // else SVGF's 5 x 5 B3-spline kernel.
    AtrousFilter(RayFrame& frame, const EdgeStops& stops, bool ffx);
    // `levels` levels over frame.filterA, each timed as "atrous"; keeps the first level's output
    // as the history's V (RayFrame::keepHistory). Returns the texture holding the result.
    GLuint run(PassClock& clock, int levels);

  private:
    RayFrame& frame_;
    GlProgram program_;
};

}  // namespace so
