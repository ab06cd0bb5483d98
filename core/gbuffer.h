// A renderer's G-buffer, the input of `trace --points` (docs/external.md, "Points in"): per pixel a
// world-space surface point, the normal of the side the renderer shades and a coverage value; the
// oracle's own gbuffer.exr also carries the ids and barycentrics that replay a hit exactly.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/scene.h"

namespace so {

struct GBuffer {
    std::string path;  // for messages and oracle.json
    int width = 0, height = 0;
    std::string coverageChannel;  // the channel read as coverage ("A" or "coverage")
    // One entry per pixel, row-major, row 0 at the top (the file's data window).
    std::vector<float> coverage;  // covered where != 0
    std::vector<float> wsPX, wsPY, wsPZ;
    std::vector<float> wsNX, wsNY, wsNZ;  // any length > 0 in covered pixels
    // The exact-replay channels id.mesh, id.prim, bary.u, bary.v: all four or none (empty; ids
    // without barycentrics, as in oracle.exr, are not read).
    std::vector<float> meshId, primId, baryU, baryV;
    std::vector<float> depth;  // Z, copied through when present (empty: absent)

    size_t pixelCount() const { return size_t(width) * size_t(height); }
    bool covered(size_t i) const { return coverage[i] != 0.0f; }
    bool hasReplay() const { return !meshId.empty(); }
    glm::dvec3 wsPoint(size_t i) const { return {wsPX[i], wsPY[i], wsPZ[i]}; }
    glm::dvec3 wsNormal(size_t i) const { return {wsNX[i], wsNY[i], wsNZ[i]}; }
};

// Reads and validates a G-buffer EXR. Throws InputError ("FILE: CHANNEL: why") on an unreadable
// file, a data window other than the display window, more than limits.maxImagePixels pixels or a
// side above limits.maxImageSide, a missing channel (P.X/Y/Z, N.X/Y/Z, a coverage channel; a
// barycentric channel without all of the other replay channels), a non-finite coverage, or a
// covered pixel with a non-finite P or N or a zero N. Only the channels above are read, so memory
// is bounded by the pixel limit.
GBuffer readGBuffer(const std::string& path, const LoadLimits& limits = {});

// The checks every reader of a user's EXR makes before OpenEXR opens it (OpenEXR 3.1 allocates
// what a header declares before any check of ours): a header walk in which every length fits the
// file, a single-part flat image whose data window equals its display window and fits
// limits.maxImageSide and limits.maxImagePixels. Throws InputError naming the file and field.
void checkExrHeader(const std::string& path, const LoadLimits& limits = {});

}  // namespace so
