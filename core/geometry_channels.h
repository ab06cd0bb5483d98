// The one writer of the per-pixel geometry channels (docs/exr-channels.md), shared by the oracle
// and the raster path so both files carry the same channels with the same fill values.
#pragma once

#include <glm/vec3.hpp>

#include "core/image.h"

namespace so {

class GeometryChannelWriter {
  public:
    // Adds A, P.*, N.*, Z, id.mesh, id.prim to `image`, filled as "no hit" (A 0, Z +inf, ids -1).
    explicit GeometryChannelWriter(ChannelImage& image);
    // One pixel that hit: world position, geometric normal, distance from the eye, ids (exact in
    // float: the loader caps meshes and triangles per mesh at 2^24).
    void set(size_t pixel, const glm::dvec3& wsPosition, const glm::vec3& normal, float depth,
             float meshId, float primId);

  private:
    float* hit_;
    float* position_[3];
    float* normal_[3];
    float* depth_;
    float* meshId_;
    float* primId_;
};

}  // namespace so
