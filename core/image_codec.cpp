#include "core/image_codec.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>

#include "core/error.h"
#include "core/image_module.h"
#include "core/png_encode.h"
#include "core/webp_decode.h"

namespace so {

namespace {

// The bytes of a PNG: grey, a third the size of RGB, where every pixel is grey (the shaded renders
// and previews), else RGB (class maps, ramps).
struct Png8 {
    int channels = 3;
    std::vector<uint8_t> pixels;
};

Png8 png8(int width, int height, const std::vector<float>& linearRgb) {
    if (width < 0 || height < 0 || linearRgb.size() != size_t(width) * size_t(height) * 3)
        throw std::invalid_argument("PNG: " + std::to_string(linearRgb.size()) + " values for a " +
                                    std::to_string(width) + " x " + std::to_string(height) +
                                    " RGB image");
    Png8 png;
    png.pixels.resize(linearRgb.size());
    for (size_t i = 0; i < linearRgb.size(); ++i) png.pixels[i] = toSrgb8(linearRgb[i]);
    bool grey = true;
    for (size_t i = 0; i < png.pixels.size() && grey; i += 3)
        grey = png.pixels[i] == png.pixels[i + 1] && png.pixels[i + 1] == png.pixels[i + 2];
    if (grey) {
        for (size_t i = 0; i < png.pixels.size() / 3; ++i) png.pixels[i] = png.pixels[3 * i];
        png.pixels.resize(png.pixels.size() / 3);
        png.channels = 1;
    }
    return png;
}

float* allocateRgba(void* allocatorData, int width, int height) {
    auto* texture = static_cast<TextureRgba*>(allocatorData);
    texture->width = width;
    texture->height = height;
    texture->rgba.assign(size_t(width) * size_t(height) * 4, 0.0f);
    return texture->rgba.data();
}

// Fills the channels the file lacks (see TextureRgba) and clamps to [0,1].
void expandToRgba(TextureRgba& t) {
    const int c = t.fileChannels;
    for (size_t i = 0; i < t.rgba.size(); i += 4) {
        float* p = &t.rgba[i];
        if (c <= 2) p[3] = c == 2 ? p[1] : 1.0f;
        if (c <= 2) p[1] = p[2] = p[0];
        if (c == 3) p[3] = 1.0f;
        for (int k = 0; k < 4; ++k) p[k] = p[k] > 0.0f ? std::min(p[k], 1.0f) : 0.0f;
    }
}

}  // namespace

uint8_t toSrgb8(float linear) {
    float c = std::clamp(linear, 0.0f, 1.0f);
    float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(s * 255.0f));
}

void writePngRgb(const std::string& path, int width, int height,
                 const std::vector<float>& linearRgb) {
    const Png8 png = png8(width, height, linearRgb);
    const std::vector<uint8_t> bytes =
        encodePng8(width, height, png.channels, png.pixels, PngEffort::Fast);
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    if (!out) throwInputError(path, "", "cannot write the PNG");
}

std::vector<unsigned char> encodePngRgb(int width, int height,
                                        const std::vector<float>& linearRgb) {
    const Png8 png = png8(width, height, linearRgb);
    return encodePng8(width, height, png.channels, png.pixels, PngEffort::Small);
}

TextureRgba readTextureRgba(const std::string& path, int maxWidth, int maxHeight,
                            uint64_t maxPixels) {
    const SoImageModule& m = imageModule();
    TextureRgba texture;
    char error[512] = "";
    if (m.readPixels(path.c_str(), maxWidth, maxHeight, maxPixels, allocateRgba, &texture,
                     &texture.fileChannels, error, sizeof error) != 0)
        throwInputError(path, "", "cannot read the image: " + printable(error, 400));
    expandToRgba(texture);
    return texture;
}

TextureRgba decodeTextureRgba(const std::vector<unsigned char>& bytes, int maxWidth, int maxHeight,
                              uint64_t maxPixels) {
    if (isWebp(bytes)) return decodeWebpRgba(bytes, maxWidth, maxHeight, maxPixels);
    const SoImageModule& m = imageModule();
    TextureRgba texture;
    char error[512] = "";
    if (m.readPixelsFromMemory(bytes.data(), bytes.size(), maxWidth, maxHeight, maxPixels,
                               allocateRgba, &texture, &texture.fileChannels, error,
                               sizeof error) != 0)
        throwInputError("(memory)", "", printable(error, 400));
    expandToRgba(texture);
    return texture;
}

std::string imageLibraryVersion() {
    return imageModule().version;
}

std::string loadedImageLibraryVersion() {
    const SoImageModule* m = imageModuleIfLoaded();
    return m ? m->version : std::string();
}

std::string base64(const std::vector<unsigned char>& b) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string o;
    o.reserve((b.size() + 2) / 3 * 4);
    for (size_t i = 0; i < b.size(); i += 3) {
        const uint32_t v = uint32_t(b[i]) << 16 | (i + 1 < b.size() ? uint32_t(b[i + 1]) << 8 : 0) |
                           (i + 2 < b.size() ? uint32_t(b[i + 2]) : 0);
        o += t[(v >> 18) & 63];
        o += t[(v >> 12) & 63];
        o += i + 1 < b.size() ? t[(v >> 6) & 63] : '=';
        o += i + 2 < b.size() ? t[v & 63] : '=';
    }
    return o;
}

}  // namespace so
