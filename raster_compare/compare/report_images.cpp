#include "raster_compare/compare/report_images.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/channels.h"
#include "core/error.h"
#include "core/image_codec.h"
#include "core/preview.h"
#include "raster_compare/compare/artifacts.h"

namespace so {

namespace ch = channels;

Rgb shadedImage(const ChannelImage& oracle, const float* V, const std::string& light) {
    return shadowGrey(oracle, V, oracle.channel(ch::lightChannel(light, ch::kCosine)));
}

Rgb classMap(const ChannelImage& oracle, const ErrorMaps& maps, const std::string& light) {
    const float* V = oracle.channel(ch::lightChannel(light, ch::kVisibility));
    const float* A = oracle.channel(ch::kHit);
    Rgb rgb(oracle.pixelCount() * 3);
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        const float grey = A[i] == 0.0f ? 0.03f : 0.12f + 0.18f * V[i];
        const float* c = maps.shown[i] ? kArtifactClasses[maps.shown[i] - 1].rgb : nullptr;
        for (int k = 0; k < 3; ++k) rgb[3 * i + size_t(k)] = c ? c[k] : grey;
    }
    return rgb;
}

Rgb visibilityGrey(const std::vector<float>& V) {
    Rgb rgb(V.size() * 3);
    for (size_t i = 0; i < V.size(); ++i)
        for (size_t k = 0; k < 3; ++k) rgb[3 * i + k] = 0.06f + 0.8f * std::clamp(V[i], 0.0f, 1.0f);
    return rgb;
}

Rgb flickerMap(const std::vector<float>& V, const std::vector<uint8_t>& mask) {
    SO_CHECK(V.size() == mask.size());
    constexpr float kFlicker[3] = {0.95f, 0.05f, 0.05f};
    Rgb rgb = visibilityGrey(V);
    for (size_t i = 0; i < V.size(); ++i)
        for (size_t k = 0; k < 3; ++k) {
            if (mask[i] == 2) rgb[3 * i + k] = kFlicker[k];
            if (mask[i] == 0) rgb[3 * i + k] *= 0.3f;  // not tracked: not measured
        }
    return rgb;
}

namespace {

std::array<float, 3> magnitudeColour(float e) {
    constexpr float stops[5][3] = {{0.05f, 0.05f, 0.08f},
                                   {0.0f, 0.45f, 0.70f},
                                   {0.80f, 0.47f, 0.65f},
                                   {0.90f, 0.62f, 0.0f},
                                   {0.98f, 0.95f, 0.70f}};
    const float t = std::clamp(e / kMagnitudeMax, 0.0f, 1.0f) * 4.0f;
    const int k = std::min(3, int(t));
    const float f = t - float(k);
    return {stops[k][0] + f * (stops[k + 1][0] - stops[k][0]),
            stops[k][1] + f * (stops[k + 1][1] - stops[k][1]),
            stops[k][2] + f * (stops[k + 1][2] - stops[k][2])};
}

}  // namespace

Rgb magnitudeMap(const ChannelImage& oracle, const ErrorMaps& maps) {
    const float* A = oracle.channel(ch::kHit);
    Rgb rgb(oracle.pixelCount() * 3, 0.03f);
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        // 128 steps over the ramp: flat runs of few colours, which PNG compresses to a fraction
        // of the smooth ramp's bytes; the error EXR has the exact values.
        const float step = kMagnitudeMax / 128.0f;
        const std::array<float, 3> c = magnitudeColour(std::round(maps.error[i] / step) * step);
        std::copy(c.begin(), c.end(), rgb.begin() + long(3 * i));
    }
    return rgb;
}

std::string magnitudeBar() {
    std::ostringstream s;
    s << "<svg class=\"bar\" viewBox=\"0 0 260 34\" width=\"260\" height=\"34\" role=\"img\" "
         "aria-label=\"error magnitude scale\"><defs><linearGradient id=\"mag\">";
    for (int k = 0; k <= 8; ++k) {
        const std::array<float, 3> c = magnitudeColour(kMagnitudeMax * float(k) / 8.0f);
        s << "<stop offset=\"" << k * 12.5 << "%\" stop-color=\"rgb(" << int(c[0] * 255) << ","
          << int(c[1] * 255) << "," << int(c[2] * 255) << ")\"/>";
    }
    s << "</linearGradient></defs><rect x=\"10\" y=\"2\" width=\"240\" height=\"12\" "
         "fill=\"url(#mag)\"/>";
    for (int k = 0; k <= 4; ++k)
        s << "<text x=\"" << 10 + 60 * k << "\" y=\"30\" class=\"tick\" text-anchor=\"middle\">"
          << kMagnitudeMax * float(k) / 4.0f << (k == 4 ? "+" : "") << "</text>";
    s << "</svg>";
    return s.str();
}

Rgb aliasingMap(const ChannelImage& raster, const std::string& light) {
    const float* AP = raster.channel(ch::lightChannel(light, ch::kPredictedAliasing));
    Rgb rgb(raster.pixelCount() * 3, 0.05f);
    for (size_t i = 0; i < raster.pixelCount(); ++i) {
        if (!(AP[i] > 0.0f)) continue;
        const float t = std::clamp(std::log2(AP[i]) / 3.0f, -1.0f, 1.0f);
        rgb[3 * i] = t > 0 ? 1.0f : 1.0f + t;
        rgb[3 * i + 1] = 1.0f - std::fabs(t);
        rgb[3 * i + 2] = t < 0 ? 1.0f : 1.0f - t;
    }
    return rgb;
}

Rgb unconvergedMap(const ChannelImage& oracle, const std::string& light, size_t& count) {
    count = 0;
    const std::string name = ch::lightChannel(light, ch::kUnconverged);
    if (!oracle.has(name)) return {};
    const float* U = oracle.channel(name);
    const float* A = oracle.channel(ch::kHit);
    Rgb rgb(oracle.pixelCount() * 3);
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        count += U[i] > 0.0f;
        const float g = A[i] == 0.0f ? 0.03f : 0.2f;
        rgb[3 * i] = U[i] > 0.0f ? 0.90f : g;
        rgb[3 * i + 1] = U[i] > 0.0f ? 0.62f : g;
        rgb[3 * i + 2] = U[i] > 0.0f ? 0.0f : g;
    }
    return count ? rgb : Rgb{};
}

// A summed-area table finds the square in O(pixels); ties go to the first in row order, so the
// choice is deterministic.
Crop worstRegion(const std::vector<float>& error, int width, int height, int size) {
    size = std::max(1, std::min({size, width, height}));
    const size_t W = size_t(width) + 1;
    std::vector<double> sat(W * (size_t(height) + 1), 0.0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            sat[(size_t(y) + 1) * W + size_t(x) + 1] =
                double(error[size_t(y) * size_t(width) + size_t(x)]) +
                sat[size_t(y) * W + size_t(x) + 1] + sat[(size_t(y) + 1) * W + size_t(x)] -
                sat[size_t(y) * W + size_t(x)];
    Crop best{0, 0, size};
    double bestSum = -1.0;
    for (int y = 0; y + size <= height; ++y)
        for (int x = 0; x + size <= width; ++x) {
            const size_t y0 = size_t(y), x0 = size_t(x), y1 = y0 + size_t(size),
                         x1 = x0 + size_t(size);
            const double s =
                sat[y1 * W + x1] - sat[y0 * W + x1] - sat[y1 * W + x0] + sat[y0 * W + x0];
            if (s > bestSum + 1e-9) bestSum = s, best = {x, y, size};
        }
    return best;
}

Rgb cropOf(const Rgb& image, int width, const Crop& crop) {
    Rgb out;
    out.reserve(size_t(crop.size) * size_t(crop.size) * 3);
    for (int y = crop.y; y < crop.y + crop.size; ++y) {
        const size_t row = (size_t(y) * size_t(width) + size_t(crop.x)) * 3;
        out.insert(out.end(), image.begin() + long(row),
                   image.begin() + long(row + size_t(crop.size) * 3));
    }
    return out;
}

ImageSink::ImageSink(std::filesystem::path folder, std::string relative)
    : folder_(std::move(folder)), relative_(std::move(relative)) {
    if (folder_.empty()) return;
    // The folder is the page's own (named after it): last run's images go, so none is stale.
    std::error_code ec;
    std::filesystem::remove_all(folder_, ec);
    std::filesystem::create_directories(folder_, ec);
    if (ec) throwInputError(folder_.string(), "", "cannot be created: " + ec.message());
}

std::string ImageSink::src(const std::string& key, int width, int height, const Rgb& rgb) {
    const std::vector<unsigned char> png = encodePngRgb(width, height, rgb);
    bytes_ += png.size();
    if (embedded()) return "data:image/png;base64," + base64(png);
    std::string name;
    for (char c : key) name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
    name += ".png";
    std::ofstream f(folder_ / name, std::ios::binary);
    f.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    if (!f) throwInputError((folder_ / name).string(), "", "cannot be written");
    return relative_ + "/" + name;
}

}  // namespace so
