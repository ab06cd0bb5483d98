// The exponential history pass (temporal.glsl) that the temporal denoiser is, and that svgf and
// penumbra run first: V and its first two moments blended into the reprojected history with
// weight `history`, the first frames of a history averaged equally (SVGF section 4.1).
#pragma once

#include "raster_compare/gl/denoisers/ray_frame.h"

namespace so {

class PassClock;

class ExponentialHistory {
  public:
    // `maxLength` caps the history's length, and so how far 1 / length lowers the new frame's
    // weight below 1 - history.
    ExponentialHistory(RayFrame& frame, double history, double maxLength = 1024);
    // Timed as "temporal": the accumulation into frame.accum.
    void run(PassClock& clock);

  private:
    RayFrame& frame_;
    GlProgram program_;
};

}  // namespace so
