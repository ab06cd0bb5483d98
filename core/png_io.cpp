// PNG previews through libpng. (OpenImageIO would do it too, but on Debian 12 it drags ~250 shared
// libraries into every process start, 0.2 s of dynamic linking per run; libpng is enough here.)
#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <unordered_map>
#include <vector>

#include <png.h>

#include "core/error.h"
#include "core/image.h"

namespace so {

static uint8_t toSrgb8(float linear) {
    float c = std::clamp(linear, 0.0f, 1.0f);
    float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(s * 255.0f));
}

void writePngRgb(const std::string& path, int width, int height,
                 const std::vector<float>& linearRgb) {
    SO_CHECK_EQ(linearRgb.size(), size_t(width) * size_t(height) * 3);
    std::vector<uint8_t> pixels(linearRgb.size());
    for (size_t i = 0; i < linearRgb.size(); ++i) pixels[i] = toSrgb8(linearRgb[i]);

    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throwInputError(path, "", "cannot create the file");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        std::fclose(f);
        throwInputError(path, "", "cannot initialise libpng");
    }
    // libpng reports errors by longjmp; nothing with a destructor lives between here and there.
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        std::fclose(f);
        throwInputError(path, "", "cannot write PNG");
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
        png_write_row(png, pixels.data() + size_t(y) * size_t(width) * 3);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fclose(f) != 0) throwInputError(path, "", "cannot finish writing the file");
}

static void appendToVector(png_structp png, png_bytep data, png_size_t length) {
    auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
    out->insert(out->end(), data, data + length);
}

namespace {

// The smallest lossless layout of 8-bit sRGB pixels: grey where every pixel is grey, a palette
// where there are at most 256 colours (class maps, quantised ramps), RGB otherwise. Report pages
// hold dozens of images, and this is a third or less of their RGB size.
struct PngLayout {
    int colorType = PNG_COLOR_TYPE_RGB;
    int bytesPerPixel = 3;
    std::vector<uint8_t> pixels;
    std::vector<png_color> palette;
};

PngLayout pngLayout(std::vector<uint8_t> rgb) {
    const size_t n = rgb.size() / 3;
    bool grey = true;
    std::unordered_map<uint32_t, uint8_t> index;
    for (size_t i = 0; i < n && (grey || index.size() <= 256); ++i) {
        const uint8_t r = rgb[3 * i], g = rgb[3 * i + 1], b = rgb[3 * i + 2];
        grey = grey && r == g && g == b;
        if (index.size() <= 256)
            index.try_emplace(uint32_t(r) << 16 | uint32_t(g) << 8 | b, uint8_t(index.size()));
    }
    PngLayout l;
    if (grey || index.size() <= 256) {
        l.colorType = grey ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_PALETTE;
        l.bytesPerPixel = 1;
        l.pixels.resize(n);
        if (!grey) {
            l.palette.resize(index.size());
            for (const auto& [c, k] : index)
                l.palette[k] = {uint8_t(c >> 16), uint8_t(c >> 8 & 0xff), uint8_t(c & 0xff)};
        }
        for (size_t i = 0; i < n; ++i)
            l.pixels[i] = grey ? rgb[3 * i]
                               : index.at(uint32_t(rgb[3 * i]) << 16 |
                                          uint32_t(rgb[3 * i + 1]) << 8 | rgb[3 * i + 2]);
        return l;
    }
    l.pixels = std::move(rgb);
    return l;
}

}  // namespace

std::vector<unsigned char> encodePngRgb(int width, int height,
                                        const std::vector<float>& linearRgb) {
    SO_CHECK_EQ(linearRgb.size(), size_t(width) * size_t(height) * 3);
    std::vector<uint8_t> srgb(linearRgb.size());
    for (size_t i = 0; i < linearRgb.size(); ++i) srgb[i] = toSrgb8(linearRgb[i]);
    const PngLayout layout = pngLayout(std::move(srgb));
    std::vector<unsigned char> out;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    SO_CHECK(png && info);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        throwInputError("(memory)", "", "cannot encode PNG");
    }
    png_set_write_fn(png, &out, appendToVector, nullptr);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, layout.colorType,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!layout.palette.empty())
        png_set_PLTE(png, info, layout.palette.data(), int(layout.palette.size()));
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    const size_t stride = size_t(width) * size_t(layout.bytesPerPixel);
    for (int y = 0; y < height; ++y) png_write_row(png, layout.pixels.data() + size_t(y) * stride);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return out;
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
