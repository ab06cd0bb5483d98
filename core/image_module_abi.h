// The C interface between core/image_codec.cpp and the OpenImageIO module
// (core/image_oiio_module.cpp), which core/image_module.cpp loads with dlopen() on the first image
// call. Plain C on purpose: no exception, allocation or C++ object crosses the boundary, so the two
// sides only have to agree on this table. Every function returns 0 on success, and otherwise
// non-zero with a one-line reason written into `error` (NUL-terminated, at most `errorSize` bytes).
#pragma once

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

// Bumped whenever the table below changes; the loader refuses a module of another version.
#define SO_IMAGE_MODULE_ABI_VERSION 2
// The one symbol the module exports: returns its table (static storage, never null).
#define SO_IMAGE_MODULE_ENTRY "so_image_module_v1"

// Receives encoded bytes, in order, as the encoder produces them.
typedef void (*SoImageByteSink)(void* sinkData, const unsigned char* bytes, size_t size);
// Returns room for width * height * 4 floats owned by the caller, or null to abandon the read.
typedef float* (*SoImageRgbaAllocator)(void* allocatorData, int width, int height);

typedef struct SoImageModule {
    uint32_t abiVersion;  // SO_IMAGE_MODULE_ABI_VERSION
    const char* version;  // OpenImageIO's, e.g. "2.4.7.1" (oracle.json's provenance)

    // 8-bit PNG of `channels` (1 to 4: grey, grey+alpha, RGB, RGBA) interleaved bytes stored as
    // given, row 0 at the top, tagged sRGB; written to `path`, or, with path null, handed to `sink`
    // (an in-memory encode). compressionLevel: zlib's 0 to 9; pngFilter: libpng's PNG_FILTER_*
    // flags (0: libpng's choice).
    int (*writePng8)(const char* path, SoImageByteSink sink, void* sinkData, int width, int height,
                     int channels, const unsigned char* pixels, int compressionLevel, int pngFilter,
                     char* error, size_t errorSize);

    // Decodes the first image of any file OpenImageIO reads. The header is checked against the
    // limits before any pixel is read; then the file's channels (1 to 4) are stored as floats of
    // their encoded values (no colour conversion, alpha not premultiplied) in the first
    // `*channels` of every 4 floats of the allocator's buffer; the rest are left untouched.
    int (*readPixels)(const char* path, int maxWidth, int maxHeight, uint64_t maxPixels,
                      SoImageRgbaAllocator allocate, void* allocatorData, int* channels,
                      char* error, size_t errorSize);

    // The same from an encoded file in memory (a glTF image in a buffer or a data: URI). PNG and
    // JPEG, told apart by their first bytes.
    int (*readPixelsFromMemory)(const unsigned char* bytes, size_t size, int maxWidth,
                                int maxHeight, uint64_t maxPixels, SoImageRgbaAllocator allocate,
                                void* allocatorData, int* channels, char* error, size_t errorSize);
} SoImageModule;

typedef const SoImageModule* (*SoImageModuleEntry)(void);

#ifdef __cplusplus
}
#endif
