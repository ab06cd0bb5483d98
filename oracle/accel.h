// The Embree scene the oracle traces: built once from the scene model, in the local frame
// (local_frame.h), robust mode, one Embree geometry per drawn mesh primitive with geomID = id.mesh.
// Keeps the double-precision local vertices so hit points and normals are rebuilt exactly.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "oracle/embree_handles.h"

namespace so {

class Accel {
  public:
    Accel(const Scene& scene, const EmbreeDevice& device);
    Accel(const Accel&) = delete;
    Accel& operator=(const Accel&) = delete;

    RTCScene rtcScene() const { return rtcScene_.get(); }
    const LocalFrame& frame() const { return frame_; }

    // Triangle `prim` of mesh `mesh`, vertices in the local frame, double.
    void triangle(unsigned mesh, unsigned prim, glm::dvec3& a, glm::dvec3& b, glm::dvec3& c) const {
        const MeshData& m = meshes_[mesh];
        a = m.lsPositions[m.indices[3 * prim]];
        b = m.lsPositions[m.indices[3 * prim + 1]];
        c = m.lsPositions[m.indices[3 * prim + 2]];
    }

  private:
    struct MeshData {
        std::vector<glm::dvec3> lsPositions;
        const std::vector<uint32_t>& indices;
    };
    LocalFrame frame_;
    EmbreeScene rtcScene_;
    std::vector<MeshData> meshes_;
};

}  // namespace so
