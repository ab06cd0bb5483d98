// The receiver of the planar families (planar projected shadows, shadow textures): a mesh given by
// its index (as id.mesh counts), or by default the largest planar mesh of the scene, and its
// plane in the local frame.
#pragma once

#include <optional>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "core/local_frame.h"
#include "core/scene.h"

namespace so {

struct ReceiverPlane {
    int mesh = -1;
    // (n, d) with n . x + d = 0 on the plane, n unit, in the local frame.
    glm::dvec4 lsPlane{0.0};
    double area = 0.0;  // the mesh's area (world units)
};

// Blinn's projection onto the plane P (points x with P . (x, 1) = 0) from the homogeneous light
// L (position, 1) or (direction towards the light, 0): (P . L) I - L P^T.
glm::dmat4 planarProjection(const glm::dvec4& P, const glm::dvec4& L);
// The orthographic projection along the plane's (unit) normal onto it: I - (n, 0) P^T.
glm::dmat4 flattenOnto(const glm::dvec4& P);

// Whether every vertex of `mesh` lies within 1e-6 of its extent of the plane through its largest
// triangle; the plane if so.
std::optional<ReceiverPlane> planeOfMesh(const MeshPrimitive& mesh, const LocalFrame& frame);

// `requested` >= 0: that mesh (it must be planar); -1: the planar mesh of largest area. Throws
// InputError naming the technique when there is none, or the mesh is not planar or out of range.
ReceiverPlane findReceiver(const Scene& scene, const LocalFrame& frame, int requested,
                           const std::string& technique);

}  // namespace so
