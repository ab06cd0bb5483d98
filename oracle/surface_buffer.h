// The primary pass: one ray per pixel centre, and what each pixel sees, in the local frame.
//
// Stored tile-major (4x4 pixel tiles, 16 consecutive entries per tile, tiles in row order) because
// the shadow passes trace one 16-ray packet per tile: they then read this buffer sequentially,
// which is what keeps the oracle close to a bare Embree packet loop (bench/).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera.h"
#include "oracle/accel.h"
#include "oracle/near_field.h"
#include "oracle/offset.h"

namespace so {

class Progress;

struct SurfaceBuffer {
    static constexpr int kTile = 4;
    // The buffer covers image rows rowBegin .. rowBegin + height - 1 (all of them unless `trace
    // --tile` asks for a band); rowBegin is a multiple of kTile, so a band holds exactly the
    // whole run's tiles. Slots and pixel indices are relative to the band.
    int width = 0, height = 0;
    int rowBegin = 0;
    int tilesX = 0, tilesY = 0;
    // The eye, local frame; none when the buffer comes from a G-buffer's points (trace --points,
    // oracle/points.h): there is no camera then, and verify.cpp skips its primary-ray check.
    std::optional<glm::dvec3> lsEye;
    // One entry per slot (tilesX * tilesY * 16); slots outside the image have hit = 0.
    std::vector<uint8_t> hit;        // 1 where the primary ray hit
    std::vector<uint32_t> meshId;    // id.mesh (Embree geomID)
    std::vector<uint32_t> primId;    // id.prim (Embree primID = triangle in index order)
    std::vector<uint32_t> originId;  // the hit triangle's Accel::originId: shadow rays skip it
    // Per-component arrays (structure of arrays): a packet's 16 lanes are then contiguous in each,
    // and its ray setup vectorises (hard_shadow.cpp).
    std::vector<float> lsPointX, lsPointY,
        lsPointZ;  // rebuilt from barycentrics on the double triangle
    std::vector<float> lsNormalX, lsNormalY,
        lsNormalZ;  // unit geometric normal (from double), facing the camera
    std::vector<float> lsOriginX, lsOriginY,
        lsOriginZ;  // offset origin for rays leaving on the normal's side
    // The origin triangle's tangency bound (offset.h): a ray whose cosine to the normal is below
    // it runs the origin filter (accel.h); +inf where every ray must.
    std::vector<float> tangentCos;
    std::vector<float> wsDepth;  // distance from the eye, world units (points: the G-buffer's Z)
    // Embree's barycentrics of the hit on triangle (meshId, primId): the point is rebuilt from
    // them on the double triangle, so they replay a hit exactly (gbuffer.exr's bary.u, bary.v;
    // trace --points, docs/external.md).
    std::vector<float> baryU, baryV;
    double lsMaxOffset = 0.0;  // the largest |origin - hit point|: the oracle's blind distance
    uint64_t alphaTests = 0;   // candidate hits on alpha-tested geometry, tested
    // The triangles each slot's shadow rays decide in double (near_field.h); built after the
    // primary pass by buildNearFields, empty before (no slot has any then).
    NearFields nearFields;

    // An empty buffer of width x height pixels from image row rowBegin: every slot a miss, at
    // infinite depth, with no origin triangle.
    static SurfaceBuffer empty(int width, int height, int rowBegin);

    size_t slotCount() const { return hit.size(); }
    glm::vec3 lsPoint(size_t s) const { return {lsPointX[s], lsPointY[s], lsPointZ[s]}; }
    glm::vec3 lsNormal(size_t s) const { return {lsNormalX[s], lsNormalY[s], lsNormalZ[s]}; }
    glm::vec3 lsRayOrigin(size_t s) const { return {lsOriginX[s], lsOriginY[s], lsOriginZ[s]}; }
    // Slot of pixel (x, y); the inverse is pixelOfSlot.
    size_t slot(int x, int y) const {
        return (size_t(y / kTile) * size_t(tilesX) + size_t(x / kTile)) * 16 +
               size_t((y % kTile) * kTile + x % kTile);
    }
    // Row-major pixel index (within the band) of a slot, or SIZE_MAX for padding slots outside
    // the image.
    size_t pixelOfSlot(size_t s) const {
        size_t tile = s / 16, k = s % 16;
        int x = int(tile % size_t(tilesX)) * kTile + int(k % kTile);
        int y = int(tile / size_t(tilesX)) * kTile + int(k / kTile);
        return (x < width && y < height) ? size_t(y) * size_t(width) + size_t(x) : SIZE_MAX;
    }
    // The pixel's row-major index in the whole image: what per-pixel seeds use, so that a pixel
    // gets the same samples whichever band traces it.
    size_t fullImagePixel(size_t pixel) const { return pixel + size_t(rowBegin) * size_t(width); }
};

// Fills slot s from a hit on triangle (mesh, prim) at Embree's barycentrics (u, v): the point
// rebuilt in double on the double triangle, the unit geometric normal turned towards `lsTowards`
// (the eye, or the side a renderer shades), the shadow-ray origin by the policy, and the tangency
// bound. wsDepth is the caller's.
struct SurfacePoint {
    glm::dvec3 lsPoint;  // the rebuilt point, double
    double lsOffset;     // how far the origin lies from it (the blind distance)
};
SurfacePoint fillSurfaceSlot(SurfaceBuffer& sb, size_t s, const Accel& accel, unsigned mesh,
                             unsigned prim, float u, float v, const glm::dvec3& lsTowards,
                             OffsetPolicy offsetPolicy);

// Traces the primary rays of image rows [rowBegin, rowEnd) in parallel (call inside the caller's
// tbb::task_arena); rowEnd -1: to the last row. rowBegin must be a multiple of kTile.
SurfaceBuffer tracePrimary(const Accel& accel, const Camera& camera, Progress* progress,
                           OffsetPolicy offsetPolicy = OffsetPolicy::ErrorBound, int rowBegin = 0,
                           int rowEnd = -1);

}  // namespace so
