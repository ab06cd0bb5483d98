// The Embree scene the oracle traces: built once from the scene model, in the local frame
// (local_frame.h), robust mode, high build quality, one Embree geometry per drawn mesh primitive
// with geomID = id.mesh (embree/triangle_scene.h, the build it shares with the raster path's
// shadow rays). Keeps the double-precision local vertices so hit points and normals are rebuilt
// exactly.
//
// Shadow rays skip the triangle they leave from: a query whose ShadowContext has the origin filter
// on rejects a hit on the triangle whose global index is the ray's `id` (kNoOriginTriangle: skip
// nothing). It is what guarantees the answer behind the tiny origin offset (offset.h), and it
// costs a callback per candidate hit, so the passes turn it on only for packets that hold a ray
// Embree's rounding could turn into its own triangle (originTangencyBound); alpha-tested
// geometries skip the origin triangle in their own filter, on every query.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "embree/embree_handles.h"
#include "embree/triangle_scene.h"

namespace so {

// The intersect context of the oracle's shadow queries: Embree's, and what the origin filter reads
// (Embree hands the context to the filter; rtc must stay the first member).
struct ShadowContext {
    RTCIntersectContext rtc;
    const unsigned* meshBase = nullptr;  // global index of each mesh's first triangle
    // The filter on (true) or off for the next queries: a hit on the ray's origin triangle is
    // then no hit.
    void originFilter(bool on);
};

// One ray for rtcIntersect1 (local frame) from org along dir, from tnear 0 to tfar, leaving from
// no surface (id kNoOriginTriangle), every mask bit set, and no hit yet.
RTCRayHit singleRayHit(const glm::vec3& org, const glm::vec3& dir, float tfar);

class Accel {
  public:
    // originFilter = false builds the plain Embree scene the benchmarks' baselines trace. Throws
    // EmbreeError where Embree fails (out of memory), std::invalid_argument for a scene the loader
    // would have rejected (non-finite vertices, uvs missing for a textured alpha mask).
    Accel(const Scene& scene, const EmbreeDevice& device, bool originFilter = true);
    Accel(const Accel&) = delete;
    Accel& operator=(const Accel&) = delete;

    RTCScene rtcScene() const { return triangles_.rtcScene(); }
    // A context for shadow queries on this scene (coherent: the packets of one tile or pixel), the
    // origin filter off.
    ShadowContext shadowContext(bool coherent) const;
    const LocalFrame& frame() const { return frame_; }

    // Triangle `prim` of mesh `mesh`, vertices in the local frame, double.
    void triangle(unsigned mesh, unsigned prim, glm::dvec3& a, glm::dvec3& b, glm::dvec3& c) const {
        triangles_.lsTriangle(mesh, prim, a, b, c);
    }
    // The same triangle as the scene gives it: world space, double (the geometry the oracle's
    // exact decisions answer for, exact_facing.h).
    void wsTriangle(unsigned mesh, unsigned prim, glm::dvec3& a, glm::dvec3& b,
                    glm::dvec3& c) const {
        triangles_.wsTriangle(mesh, prim, a, b, c);
    }
    // The ray id that makes a shadow ray skip triangle `prim` of mesh `mesh` (< 2^28 by the
    // loader's limits, so it never equals kNoOriginTriangle).
    unsigned originId(unsigned mesh, unsigned prim) const {
        return triangles_.globalIndex(mesh, prim);
    }
    // Whether its queries may run the origin filter (and the passes decide near fields): false
    // for the benchmarks' plain scene, whose passes then trace bare.
    bool filters() const { return filters_; }
    // Whether some mesh is alpha-tested: its geometry filter reads every ray's id, on every query.
    bool alphaTested() const { return triangles_.alphaTested(); }

    // Alpha tests (core/alpha_mask.h) run by this thread's filter calls so far, over all Accels:
    // a pass reads it before and after its work on each thread (alpha_tests in oracle.json).
    static uint64_t alphaTestsOnThisThread() { return TriangleScene::alphaTestsOnThisThread(); }

    // What the filter of an alpha-tested geometry reads (its Embree user data).
    using AlphaGeometry = so::AlphaGeometry;

    // What an alpha-tested mesh's filter reads; null for other meshes.
    const AlphaGeometry* alphaGeometry(unsigned mesh) const {
        return triangles_.alphaGeometry(mesh);
    }

  private:
    LocalFrame frame_;
    bool filters_ = true;
    TriangleScene triangles_;
};

}  // namespace so
