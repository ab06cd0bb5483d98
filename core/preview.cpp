#include "core/preview.h"

#include <algorithm>

#include "core/channels.h"
#include "core/image_codec.h"

namespace so {

std::vector<float> shadowGrey(const ChannelImage& image, const float* V, const float* cosine) {
    const float* A = image.channel(channels::kHit);
    std::vector<float> rgb(image.pixelCount() * 3);
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        const float c = cosine ? std::max(cosine[i], 0.0f) : 1.0f;
        const float g = A[i] == 0.0f ? 0.05f : 0.08f + 0.8f * c * V[i];
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = g;
    }
    return rgb;
}

std::vector<std::string> writePreviews(const std::filesystem::path& dir, const ChannelImage& image,
                                       const std::vector<Light>& lights) {
    namespace ch = channels;
    std::vector<std::string> paths;
    for (const Light& light : lights) {
        const std::string cosName = ch::lightChannel(light.name, ch::kCosine);
        const float* V = image.channel(ch::lightChannel(light.name, ch::kVisibility));
        const float* cosine = image.has(cosName) ? image.channel(cosName) : nullptr;
        paths.push_back((dir / (light.name + ".png")).string());
        writePngRgb(paths.back(), image.width(), image.height(), shadowGrey(image, V, cosine));
    }
    return paths;
}

}  // namespace so
