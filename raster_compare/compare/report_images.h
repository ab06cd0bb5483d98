// The pictures of the report (docs/report.md): the shaded renders, the error maps by class and by
// magnitude, predicted aliasing, the oracle's unconverged pixels, the worst region of an error
// map, and where the encoded PNGs go (into the page, or into files beside it).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "raster_compare/compare/metrics.h"

namespace so {

// Linear RGB, interleaved, as core/image_codec.h's PNG encoder takes it.
using Rgb = std::vector<float>;

// The oracle's cosine times a visibility V of `light`, so a person sees the shadows.
Rgb shadedImage(const ChannelImage& oracle, const float* V, const std::string& light);
// Every wrong pixel in the colour of the one class it is shown as (artifacts.h), over the dimmed
// truth: the coloured pixels are exactly the false-shadow and false-lit ones.
Rgb classMap(const ChannelImage& oracle, const ErrorMaps& maps, const std::string& light);
// Area lights: the error beyond the oracle's interval per pixel on a sequential ramp readable with
// any colour vision (black 0, blue, pink, orange, pale yellow at kMagnitudeMax and above).
inline constexpr float kMagnitudeMax = 0.5f;
Rgb magnitudeMap(const ChannelImage& oracle, const ErrorMaps& maps);
// The ramp's numbered bar (inline SVG).
std::string magnitudeBar();
// The texel's footprint over the pixel's on a log ramp: blue < 1 (white) < red, saturating at 1/8
// and 8.
Rgb aliasingMap(const ChannelImage& raster, const std::string& light);
// The oracle's pixels that spent their budget short of the target, orange over grey; empty when
// there are none (or the light is not sampled).
Rgb unconvergedMap(const ChannelImage& oracle, const std::string& light, size_t& count);

// The flicker strip (compare --frames-path): a frame's V as grey, and the same with the pixels
// of a temporal.h mask that flicker in red and those not tracked dimmed.
Rgb visibilityGrey(const std::vector<float>& V);
Rgb flickerMap(const std::vector<float>& V, const std::vector<uint8_t>& mask);

// A square of the image: the one with the largest summed error.
struct Crop {
    int x = 0, y = 0, size = 0;
};
Crop worstRegion(const std::vector<float>& error, int width, int height, int size);
Rgb cropOf(const Rgb& image, int width, const Crop& crop);

// Encodes PNGs and gives the <img> src for each: a data: URI (embedded), or a file written into
// `folder` named by its key, linked relative to the page (beside).
class ImageSink {
  public:
    // folder empty: embed. Otherwise `folder` must be `page's folder / relative`.
    ImageSink(std::filesystem::path folder, std::string relative);
    std::string src(const std::string& key, int width, int height, const Rgb& rgb);
    bool embedded() const { return folder_.empty(); }
    uint64_t bytes() const { return bytes_; }

  private:
    std::filesystem::path folder_;
    std::string relative_;
    uint64_t bytes_ = 0;
};

}  // namespace so
