// Image files in and out: PNG previews and report images, and textures (alpha masks). PNGs are
// written with zlib alone (core/png_encode.h); reading is done by OpenImageIO in a module loaded on
// the first read (core/image_module.h), so a process that never reads an image never loads it.
// Each throws InputError naming the file (or the module) on failure.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace so {

// A linear value in [0,1] (clamped) as an 8-bit sRGB code: what every PNG we write stores.
uint8_t toSrgb8(float linear);

// 8-bit sRGB PNG from linear RGB floats in [0,1] (interleaved, row 0 at the top): one grey channel
// where every pixel is grey (R = G = B after encoding), RGB otherwise; lossless either way.
void writePngRgb(const std::string& path, int width, int height,
                 const std::vector<float>& linearRgb);
// linearRgb must hold width * height * 3 values (else std::invalid_argument).
// The same PNG in memory (the report's images).
std::vector<unsigned char> encodePngRgb(int width, int height, const std::vector<float>& linearRgb);
// For data: URIs.
std::string base64(const std::vector<unsigned char>& bytes);
// The version of OpenImageIO that reads them (loads the module).
std::string imageLibraryVersion();
// The same if this process has loaded the module (it read an image), else empty; loads nothing.
std::string loadedImageLibraryVersion();

// A decoded texture: interleaved RGBA, row 0 at the top, every value in [0,1]. The values are the
// file's encoded ones: an sRGB-encoded colour stays sRGB-encoded (no linearisation; the caller
// knows whether the texture holds colour or data), and alpha, linear by definition, is read as
// stored (not premultiplied into the colour). Files with fewer channels are expanded as PNG and
// glTF define them: grey gives R = G = B = grey and alpha 1, grey+alpha gives R = G = B = grey,
// RGB gives alpha 1. Float files (EXR, HDR) are clamped to [0,1], NaN to 0.
struct TextureRgba {
    int width = 0, height = 0;
    int fileChannels = 0;  // 1 to 4, before the expansion
    std::vector<float> rgba;
};

// Decodes the first image of any file OpenImageIO reads (PNG, JPEG, ...; 8 or 16 bit or float).
// The header is checked before any pixel is read: a file wider or taller than the limits, with
// more pixels than maxPixels, or with other than 1 to 4 channels is refused. Throws InputError
// naming the file for a missing, broken, unsupported or oversized file.
TextureRgba readTextureRgba(const std::string& path, int maxWidth = 8192, int maxHeight = 8192,
                            uint64_t maxPixels = uint64_t(1) << 26);
// The same from a PNG, JPEG or WebP file's bytes in memory (glTF images in buffers or data: URIs;
// WebP through libwebp, core/webp_decode.h, within the same limits); the InputError names
// "(memory)" as the file, for the caller to name its own.
TextureRgba decodeTextureRgba(const std::vector<unsigned char>& bytes, int maxWidth = 8192,
                              int maxHeight = 8192, uint64_t maxPixels = uint64_t(1) << 26);

}  // namespace so
