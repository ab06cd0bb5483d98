// A scene's triangle meshes as one Embree scene: the build that the oracle's acceleration
// structure (oracle/accel.h) and the raster path's shadow rays
// (raster_compare/gl/rays/shadow_rays.h) share, written once (issue 62). Vertices go to Embree in
// the caller's local frame (core/local_frame.h), float, from the double positions this keeps; one
// Embree geometry per mesh primitive, geomID = its index in scene.meshes (an empty mesh too, so
// the ids stay the scene's). A triangle's global index (its mesh's first triangle's plus its own)
// fits a ray id below kNoOriginTriangle.
//
// Alpha-tested meshes (core/alpha_mask.h) carry a filter that runs at every candidate hit of
// every query on them: where the material's alpha is below its cutoff the hit is no hit, the
// texture coordinate interpolated with Embree's barycentrics as the raster path interpolates it
// across the triangle. Where the options ask, the same filter also skips the triangle the ray
// leaves from (the ray's id holds its global index): the oracle's origin guarantee (offset.h).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "embree/embree_handles.h"

namespace so {

// The ray `id` of rays that leave from no surface (primary rays, and every ray of a scene whose
// filters do not skip an origin triangle).
inline constexpr unsigned kNoOriginTriangle = 0xFFFFFFFFu;

// How the scene is built: the oracle's defaults (a ground truth, built once and traced many
// times); the raster path's shadow rays take Embree's plain build (shadow_rays.cpp says why).
struct TriangleSceneOptions {
    // RTC_SCENE_FLAG_ROBUST: watertight along shared edges (contact lines, closed meshes).
    bool robust = true;
    // RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION: queries may run a filter of their intersect context.
    bool contextFilter = false;
    RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH;
    // A triangle of zero area in double (local frame) goes to Embree as (i, i, i), zero area in
    // float too, so never hit: its three roundings to float are independent, and a triangle
    // degenerate in double can be a sliver in float that Embree hits (docs/hard-cases.md). The
    // triangle keeps its index, so primID stays that of the scene's index buffer.
    bool dropDegenerates = true;
    // Alpha-tested geometries' filters also reject a hit on the ray's origin triangle (ray id).
    bool alphaSkipsOrigin = false;
};

// What the filter of an alpha-tested geometry reads (its Embree user data).
struct AlphaGeometry {
    unsigned base = 0;  // global index of the mesh's first triangle
    bool skipOrigin = false;
    const AlphaMask* mask = nullptr;
    const AlphaTexture* texture = nullptr;  // null: constant alpha
    const glm::vec2* uvs = nullptr;         // per vertex
    const uint32_t* indices = nullptr;      // 3 per triangle
};

class TriangleScene {
  public:
    // `scene` must outlive this (the filters and wsTriangle read its meshes), and so must
    // `device`. Throws EmbreeError where Embree fails (out of memory), std::invalid_argument for
    // a scene the loader would have rejected (non-finite vertices, uvs missing for a textured
    // alpha mask, more than 2^32 - 2 triangles).
    TriangleScene(const Scene& scene, const LocalFrame& frame, const EmbreeDevice& device,
                  const TriangleSceneOptions& options);
    TriangleScene(const TriangleScene&) = delete;
    TriangleScene& operator=(const TriangleScene&) = delete;

    RTCScene rtcScene() const { return rtcScene_.get(); }

    // Triangle `prim` of mesh `mesh`, vertices in the local frame, double.
    void lsTriangle(unsigned mesh, unsigned prim, glm::dvec3& a, glm::dvec3& b,
                    glm::dvec3& c) const {
        const MeshData& m = meshes_[mesh];
        a = m.lsPositions[m.indices[3 * prim]];
        b = m.lsPositions[m.indices[3 * prim + 1]];
        c = m.lsPositions[m.indices[3 * prim + 2]];
    }
    // The same triangle as the scene gives it: world space, double.
    void wsTriangle(unsigned mesh, unsigned prim, glm::dvec3& a, glm::dvec3& b,
                    glm::dvec3& c) const {
        const MeshData& m = meshes_[mesh];
        a = m.wsPositions[m.indices[3 * prim]];
        b = m.wsPositions[m.indices[3 * prim + 1]];
        c = m.wsPositions[m.indices[3 * prim + 2]];
    }
    // The global index of triangle `prim` of mesh `mesh` (< kNoOriginTriangle).
    unsigned globalIndex(unsigned mesh, unsigned prim) const { return meshBase_[mesh] + prim; }
    // Global index of each mesh's first triangle, by mesh.
    const std::vector<unsigned>& meshBase() const { return meshBase_; }
    // Whether some mesh is alpha-tested: its geometry filter runs on every query.
    bool alphaTested() const { return !alphaGeometries_.empty(); }
    // What an alpha-tested mesh's filter reads; null for other meshes.
    const AlphaGeometry* alphaGeometry(unsigned mesh) const { return alphaByMesh_[mesh]; }

    // Alpha tests run by this thread's filter calls so far, over all TriangleScenes: a pass reads
    // it before and after its work on each thread.
    static uint64_t alphaTestsOnThisThread();

  private:
    struct MeshData {
        std::vector<glm::dvec3> lsPositions;
        const std::vector<glm::dvec3>& wsPositions;  // the scene's
        const std::vector<uint32_t>& indices;
    };
    void addMesh(const Scene& scene, size_t id, const LocalFrame& frame, const EmbreeDevice& device,
                 const TriangleSceneOptions& options);

    EmbreeScene rtcScene_;
    std::vector<MeshData> meshes_;
    std::vector<unsigned> meshBase_;
    std::vector<const AlphaGeometry*> alphaByMesh_;
    std::vector<std::unique_ptr<AlphaGeometry>> alphaGeometries_;
};

}  // namespace so
