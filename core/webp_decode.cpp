#include "core/webp_decode.h"

#include <cstring>
#include <string>

#include <webp/decode.h>

#include "core/error.h"

namespace so {

bool isWebp(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 &&
           std::memcmp(bytes.data() + 8, "WEBP", 4) == 0;
}

TextureRgba decodeWebpRgba(const std::vector<unsigned char>& bytes, int maxWidth, int maxHeight,
                           uint64_t maxPixels) {
    WebPBitstreamFeatures features;
    if (WebPGetFeatures(bytes.data(), bytes.size(), &features) != VP8_STATUS_OK)
        throwInputError("(memory)", "", "not a valid WebP file (its header does not read)");
    const int w = features.width, h = features.height;
    if (w <= 0 || h <= 0 || w > maxWidth || h > maxHeight || uint64_t(w) * uint64_t(h) > maxPixels)
        throwInputError("(memory)", "",
                        "a WebP image of " + std::to_string(w) + " x " + std::to_string(h) +
                            " pixels, over the limits (" + std::to_string(maxWidth) + " x " +
                            std::to_string(maxHeight) + ", " + std::to_string(maxPixels) +
                            " pixels)");
    if (features.has_animation)
        throwInputError("(memory)", "", "an animated WebP file (only still images are read)");
    std::vector<uint8_t> rgba8(size_t(w) * size_t(h) * 4);
    if (!WebPDecodeRGBAInto(bytes.data(), bytes.size(), rgba8.data(), rgba8.size(), w * 4))
        throwInputError("(memory)", "", "the WebP data does not decode (truncated or broken)");
    TextureRgba t;
    t.width = w;
    t.height = h;
    t.fileChannels = features.has_alpha ? 4 : 3;
    t.rgba.resize(rgba8.size());
    for (size_t i = 0; i < rgba8.size(); ++i) t.rgba[i] = float(rgba8[i]) / 255.0f;
    return t;
}

}  // namespace so
