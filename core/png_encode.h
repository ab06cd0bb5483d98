// 8-bit PNG encoding with zlib alone (the PNG spec, ISO/IEC 15948): previews and report images are
// written without loading OpenImageIO, whose ~250 shared libraries cost a process 0.2 to 0.6 s to
// load here (docs/benchmarks.md, "The whole process"). Decoding stays with OpenImageIO.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace so {

// How hard zlib works: the previews a trace writes are read once by a person (Fast); the report's
// images are embedded in HTML pages that are kept and shared (Small).
enum class PngEffort : uint8_t { Fast, Small };

// A PNG of `channels` (1 grey or 3 RGB) 8-bit samples per pixel, row 0 at the top, no interlace,
// one filter for every row (SUB for grey images, whose smooth shading it predicts well, none for
// RGB ones: flat areas of few colours). Deterministic: the same pixels give the same bytes.
// Throws std::invalid_argument for a size that does not match or is out of PNG's range.
std::vector<uint8_t> encodePng8(int width, int height, int channels,
                                const std::vector<uint8_t>& pixels, PngEffort effort);

// "zlib 1.2.13": the library that compresses them.
std::string pngLibraryVersion();

}  // namespace so
