// The one grey scale of every picture of shadows (the previews of trace and raster, the report's
// images): background dark, surfaces 0.08 + 0.8 * max(cos, 0) * V, linear.
#pragma once

#include <vector>

#include "core/image.h"

namespace so {

// Linear RGB, interleaved; `image` supplies A (hit). `cosine` may be null (taken as 1: the
// raster path has no cosine channel).
std::vector<float> shadowGrey(const ChannelImage& image, const float* V, const float* cosine);

}  // namespace so
