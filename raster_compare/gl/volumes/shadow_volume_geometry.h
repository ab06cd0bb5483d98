// The shadow volumes of a scene for one light, built on the CPU (docs/techniques.md, shadow
// volumes). No GL here: the geometry is plain arrays, tested on its own.
//
// Every triangle that is not edge-on to the light casts, oriented to face the light (its facing
// from its geometric normal in double, as the oracle's): its volume is the region behind it,
// bounded by the triangle (the near cap), a quad on each edge extruded to infinity (w = 0) and
// the triangle at infinity (the far cap). Summed over triangles, the quads on an edge shared by
// two casters cancel when they face the light alike (the edge is inside the silhouette), so per
// edge (vertices welded by position in the local frame) the signed count of its casters' edges
// gives how many quads it keeps and which way they face: the silhouette edges of closed meshes
// keep two (one per side), the edges of open or non-manifold meshes as many as do not cancel. So
// the stencil count at a point is the number of triangles between it and the light, whatever the
// mesh: closed, open (a single quad), non-manifold, or wound either way.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/local_frame.h"
#include "core/scene.h"

namespace so {

// The scene's triangles in the local frame with their corners' vertex ids, vertices welded by
// exact position (glTF splits them at seams): the adjacency every light's volumes are built from,
// made once per scene.
struct WeldedScene {
    std::vector<glm::dvec3> lsPositions;             // per welded vertex
    std::vector<std::array<uint32_t, 3>> triangles;  // in the meshes' order and winding
    std::vector<size_t> meshFirstTriangle;           // per mesh, its first triangle's index
    static WeldedScene build(const Scene& scene, const LocalFrame& frame);
};

struct ShadowVolumeGeometry {
    // Near caps: 3 vertices (x, y, z) per casting triangle at the float positions and in the
    // vertex order the scene is drawn with, so that their depths are the camera pass's to the bit
    // (the rasteriser's interpolation depends on the order): first the triangles whose winding
    // faces the light, then the `nearCapsFlipped` others, to be drawn with the opposite winding
    // taken as front (glFrontFace).
    std::vector<float> nearCaps;
    size_t nearCapsFlipped = 0;
    // Quads on the kept edges as two triangles each, and far caps: 4 floats (x, y, z, w) per
    // vertex, w = 0 for points at infinity. Every face is wound to face out of its volume.
    std::vector<float> sides, farCaps;
    size_t casters = 0;  // triangles that cast (not edge-on, not degenerate)
    size_t quads = 0;    // side quads kept
    // The triangles a technique draws: z-pass draws the sides only, z-fail all.
    size_t sideTriangles() const { return 2 * quads; }
    size_t allTriangles() const { return 2 * quads + 2 * casters; }
};

// lsLight: (position, 1) for point and spot lights (and area lights at their centre), (the
// direction light travels, 0) for directional lights; in the local frame.
ShadowVolumeGeometry buildShadowVolumes(const WeldedScene& scene, const glm::dvec4& lsLight);

// The casters' silhouette from lsLight: the welded edges whose signed count is non-zero (the
// edges that keep side quads above), each as (a, b) with the casters that face the light running
// from a to b (or, for a count of -1, the other way round: swapped so). The triangles of mesh
// `skipMesh` (-1: none) do not cast. In id order, so deterministic.
std::vector<std::array<uint32_t, 2>> silhouetteEdges(const WeldedScene& scene,
                                                     const glm::dvec4& lsLight, int skipMesh);

// The number of volumes that contain lsEye: casting triangles crossed by the segment from it to
// the light (for a directional light, the ray towards it). What a z-pass count must start from.
int volumesContaining(const WeldedScene& scene, const glm::dvec4& lsLight, const glm::dvec3& lsEye);

}  // namespace so
