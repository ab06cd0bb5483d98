// The a-trous levels (atrous.glsl) that svgf ends with: V and its variance filtered at
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
    AtrousFilter(RayFrame& frame, const EdgeStops& stops);
    // `levels` levels over frame.filterA, each timed as "atrous"; keeps the first level's output
    // as the history's V (RayFrame::keepHistory). Returns the texture holding the result.
    GLuint run(PassClock& clock, int levels);

  private:
    RayFrame& frame_;
    GlProgram program_;
};

}  // namespace so
