// WebP textures (glTF's EXT_texture_webp) decoded with libwebp. OpenImageIO 2.4 as Debian 12 ships
// it reads WebP only from a file name, not from memory, and glTF images come from buffers and
// data: URIs as often as from files; libwebp decodes from memory, with the header read first.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image_codec.h"

namespace so {

// Whether `bytes` start like a WebP file (a RIFF container of form type "WEBP").
bool isWebp(const std::vector<unsigned char>& bytes);

// The first image of a still WebP file. The header is read before any pixel is decoded: a file
// wider or taller than the limits, with more pixels than maxPixels, or animated, is refused.
// Throws InputError naming "(memory)" as the file, as decodeTextureRgba does.
TextureRgba decodeWebpRgba(const std::vector<unsigned char>& bytes, int maxWidth, int maxHeight,
                           uint64_t maxPixels);

}  // namespace so
