// The lightmap's atlas (docs/techniques.md, "Lightmaps"): where every static triangle of the scene
// lies in one texture. A mesh with TEXCOORD_1 keeps its own layout, scaled to the density; every
// other static mesh is cut into charts, each a connected set of coplanar triangles projected onto
// their plane (a triangle alone is the smallest chart), and the charts' rectangles are
// shelf-packed, tallest first, with `padding` empty texels around each. Meshes marked dynamic are
// left out. Pure CPU (no GL) and deterministic: the same scene and settings give the same atlas,
// bit for bit.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/scene.h"

namespace so {

struct AtlasSettings {
    double texelsPerUnit = 32.0;         // texels per world unit of surface, along each side
    int padding = 2;                     // empty texels around each chart (between two: twice that)
    std::string technique = "lightmap";  // for errors: "technique NAME: texels_per_unit: ..."
};

// The atlas's bounds (docs/techniques.md): either side (GL's usual largest texture), and its
// texels in all: 2^24 holds 16 MiB of GL_R8 per light, and the bake's targets, 38 bytes a texel
// while it runs, 608 MiB. A setting beyond them is an input error naming texels_per_unit.
inline constexpr int kMaxAtlasSide = 16384;
inline constexpr uint64_t kMaxAtlasTexels = uint64_t(1) << 24;

// A chart: triangles of one mesh that share a rectangle of the atlas.
struct AtlasChart {
    size_t mesh = 0;
    std::vector<uint32_t> triangles;          // the mesh's triangle indices (id.prim), in BFS order
    int x = 0, y = 0, width = 0, height = 0;  // its texels: [x, x + width) x [y, y + height)
    bool fromTexcoord1 = false;
};

struct LightmapAtlas {
    int width = 0, height = 0;  // texels
    std::vector<AtlasChart> charts;
    // Per mesh and triangle: the atlas coordinates of its three corners in texels (texel (i, j)
    // covers [i, i + 1) x [j, j + 1), its centre at (i + 0.5, j + 0.5)); all zero for a triangle
    // that is not baked.
    std::vector<std::vector<std::array<glm::dvec2, 3>>> corners;
    // Per mesh and triangle: the index of its chart, or -1 where it is not baked (a zero-area
    // triangle, which nothing sees, or a dynamic mesh's).
    std::vector<std::vector<int32_t>> chartOf;
    size_t dynamicMeshes = 0, dynamicTriangles = 0;  // left out: "dynamic": true
    size_t bakedTriangles = 0;
    size_t texcoord1Meshes = 0;  // meshes laid out by their own TEXCOORD_1
    uint64_t texels() const { return uint64_t(width) * uint64_t(height); }
};

// Throws InputError ("technique NAME", "texels_per_unit") where the atlas would exceed the limits,
// and ("MESH NAME", "TEXCOORD_1") for a mesh whose lightmap coordinates cannot be used (not one per
// vertex, or spanning no area).
LightmapAtlas buildLightmapAtlas(const Scene& scene, const AtlasSettings& settings);

}  // namespace so
