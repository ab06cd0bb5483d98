// The one grey scale of every picture of shadows (the previews of trace and raster, the report's
// images): background dark, surfaces 0.08 + 0.8 * max(cos, 0) * V, linear.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"

namespace so {

// Linear RGB, interleaved; `image` supplies A (hit). `cosine` may be null (taken as 1: the
// raster path has no cosine channel).
std::vector<float> shadowGrey(const ChannelImage& image, const float* V, const float* cosine);

// One PNG per light, "<dir>/<light>.png", in this grey scale (with the light's cosine channel when
// the image has one): the previews beside oracle.exr and raster.exr. Returns the paths written.
std::vector<std::string> writePreviews(const std::filesystem::path& dir, const ChannelImage& image,
                                       const std::vector<Light>& lights);

}  // namespace so
