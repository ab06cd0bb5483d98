// Back faces that cast no shadow of their own (docs/oracle.md, "Exact penumbrae"). Take a closed,
// consistently oriented surface C (a connected part of a mesh whose every edge is shared by
// exactly two of its triangles running it in opposite directions) that does not pass through
// itself: it bounds a solid, its winding number is 0 outside and s inside (s = +1 wound outwards,
// -1 inwards, the sign of its signed volume), and crossing a triangle against its normal adds 1.
// A segment that starts outside and crosses C at all first crosses it entering; one that starts
// inside, leaving. So from a point outside, the union of the shadows of C's triangles is the union
// of those of the triangles that the entering crossing can pass (the point in front of them for
// s = +1, behind for s = -1), and from inside the other half: the exact penumbra pass leaves the
// rest out of its union, which then holds about half the triangles. Each closed part of a mesh is
// taken on its own (the union over parts is the union of the parts' unions), so nested shells and
// separate closed parts are fine; a part that is not closed keeps every triangle.
//
// Which side a pixel's point is on: the camera's. The point is the camera ray's first hit, so the
// ray crossed no triangle of C before it, and the point's side towards the camera (where the
// pixel's normal points, and where its segments to the light start) lies in the same region as
// the camera. The camera's region is C's generalized winding number there (its triangles' signed
// solid angles over 4 pi); a part whose number is not within 1e-3 of 0 or s keeps every triangle.
// Alpha-tested meshes keep every triangle (their holes let the camera ray through). A closed part
// that passes through itself is outside what this covers (its winding number may be 2 in places).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "oracle/exact_scene.h"

namespace so {

// Per mesh, per triangle: +1 keep the triangle only where the point is in front of it, -1 only
// where the point is behind it, 0 always. An empty list: every triangle of the mesh kept.
using MeshFacing = std::vector<std::vector<int8_t>>;

// For points seen from lsEye (the camera, in the exact scene's frame).
MeshFacing meshFacing(const ExactScene& scene, const glm::dvec3& lsEye);

// The per-triangle keep flags of one mesh (3 indices per triangle) seen from lsEye.
std::vector<int8_t> triangleFacing(const std::vector<glm::dvec3>& positions,
                                   const std::vector<uint32_t>& indices, const glm::dvec3& lsEye);

}  // namespace so
