// The receiver of the planar families (planar projected shadows, shadow textures): a mesh given by
// its index (as id.mesh counts), or by default the largest planar mesh of the scene, and its
// plane in the local frame.
#pragma once

#include <optional>
#include <string>

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

// Whether every vertex of `mesh` lies within 1e-6 of its extent of the plane through its largest
// triangle; the plane if so.
std::optional<ReceiverPlane> planeOfMesh(const MeshPrimitive& mesh, const LocalFrame& frame);

// `requested` >= 0: that mesh (it must be planar); -1: the planar mesh of largest area. Throws
// InputError naming the technique when there is none, or the mesh is not planar or out of range.
ReceiverPlane findReceiver(const Scene& scene, const LocalFrame& frame, int requested,
                           const std::string& technique);

}  // namespace so
