// The scene's triangles in double precision in the oracle's local frame, with the exact tracer
// over them: what `--verify` (verify.h) and the exact penumbra pass (exact_penumbra.h) share. Holds
// about 200 bytes per triangle (the double vertices, the tracer's triangles and nodes).
// Alpha-tested meshes are tested by exact_alpha.h, which reads the scene's coordinates and textures
// in place: the scene must outlive this.
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "oracle/exact_alpha.h"
#include "oracle/exact_tracer.h"

namespace so {

class ExactScene {
  public:
    ExactScene(const Scene& scene, const LocalFrame& frame);
    const ExactTracer& tracer() const { return tracer_; }
    // Triangle id's vertices, local frame, double.
    std::array<glm::dvec3, 3> triangle(TriangleId id) const;
    // The point at barycentrics (u, v) of triangle id (u weighs vertex 1, v vertex 2), rebuilt on
    // the double vertices, and the triangle's unit normal turned to the side of `facing`.
    glm::dvec3 point(TriangleId id, double u, double v) const;
    glm::dvec3 normal(TriangleId id, const glm::dvec3& facing) const;
    size_t meshCount() const { return lsPositions_.size(); }
    const std::vector<glm::dvec3>& positions(uint32_t mesh) const { return lsPositions_.at(mesh); }
    const std::vector<uint32_t>& indices(uint32_t mesh) const { return *indices_.at(mesh); }
    bool alphaTested(uint32_t mesh) const { return tracer_.alphaTested({mesh, 0}); }

  private:
    std::vector<std::vector<glm::dvec3>> lsPositions_;
    std::vector<const std::vector<uint32_t>*> indices_;
    ExactAlpha alpha_;  // before tracer_, which holds a pointer to it
    ExactTracer tracer_;
};

}  // namespace so
