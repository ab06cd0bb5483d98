#include "oracle/surface_buffer.h"

#include <atomic>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/progress.h"
#include "oracle/tile_rows.h"

namespace so {

SurfaceBuffer SurfaceBuffer::empty(int width, int height, int rowBegin) {
    SurfaceBuffer sb;
    sb.width = width;
    sb.height = height;
    sb.rowBegin = rowBegin;
    sb.tilesX = (sb.width + SurfaceBuffer::kTile - 1) / SurfaceBuffer::kTile;
    sb.tilesY = (sb.height + SurfaceBuffer::kTile - 1) / SurfaceBuffer::kTile;
    const size_t n = size_t(sb.tilesX) * size_t(sb.tilesY) * 16;
    sb.hit.assign(n, 0);
    sb.meshId.assign(n, 0);
    sb.primId.assign(n, 0);
    sb.originId.assign(n, kNoOriginTriangle);
    for (auto* v :
         {&sb.lsPointX, &sb.lsPointY, &sb.lsPointZ, &sb.lsNormalX, &sb.lsNormalY, &sb.lsNormalZ,
          &sb.lsOriginX, &sb.lsOriginY, &sb.lsOriginZ, &sb.baryU, &sb.baryV})
        v->assign(n, 0.0f);
    sb.wsDepth.assign(n, std::numeric_limits<float>::infinity());
    sb.tangentCos.assign(n, std::numeric_limits<float>::infinity());
    return sb;
}

SurfacePoint fillSurfaceSlot(SurfaceBuffer& sb, size_t s, const Accel& accel, unsigned mesh,
                             unsigned prim, float u, float v, const glm::dvec3& lsTowards,
                             OffsetPolicy offsetPolicy) {
    glm::dvec3 a, b, c;
    accel.triangle(mesh, prim, a, b, c);
    // Rebuilt on the double triangle, not org + t*dir: the hit then lies on the surface to the
    // precision of the stored float whatever the ray's length.
    const glm::dvec3 p = (1.0 - double(u) - double(v)) * a + double(u) * b + double(v) * c;
    glm::dvec3 ng = glm::cross(b - a, c - a);
    ng /= glm::length(ng);  // a hit triangle has non-zero area
    if (glm::dot(ng, lsTowards) < 0.0) ng = -ng;
    sb.hit[s] = 1;
    sb.meshId[s] = mesh;
    sb.primId[s] = prim;
    sb.originId[s] = accel.originId(mesh, prim);
    const glm::vec3 pf(p), nf(ng);
    const bool errorBound = offsetPolicy == OffsetPolicy::ErrorBound;
    const glm::vec3 org = errorBound ? errorBoundOrigin(p, ng) : offsetRayOrigin(pf, nf);
    sb.lsPointX[s] = pf.x, sb.lsPointY[s] = pf.y, sb.lsPointZ[s] = pf.z;
    sb.lsNormalX[s] = nf.x, sb.lsNormalY[s] = nf.y, sb.lsNormalZ[s] = nf.z;
    sb.lsOriginX[s] = org.x, sb.lsOriginY[s] = org.y, sb.lsOriginZ[s] = org.z;
    // The bound holds for the error-bound origin only: the legacy rule's rays always filter.
    sb.tangentCos[s] =
        errorBound ? originTangencyBound(a, b, c) : std::numeric_limits<float>::infinity();
    sb.baryU[s] = u;
    sb.baryV[s] = v;
    return {p, glm::length(glm::dvec3(org) - p)};
}

SurfaceBuffer tracePrimary(const Accel& accel, const Camera& camera, Progress* progress,
                           OffsetPolicy offsetPolicy, int rowBegin, int rowEnd) {
    if (rowEnd < 0) rowEnd = camera.height();
    SO_CHECK(rowBegin % SurfaceBuffer::kTile == 0 && 0 <= rowBegin && rowBegin < rowEnd &&
             rowEnd <= camera.height());
    SurfaceBuffer sb = SurfaceBuffer::empty(camera.width(), rowEnd - rowBegin, rowBegin);
    sb.lsEye = accel.frame().lsFromWs(camera.wsEye());
    const glm::dvec3 lsEye = *sb.lsEye;
    const glm::vec3 lsEyeF(lsEye);

    // Per-tile-row maxima, reduced in a fixed order afterwards so the result is thread-count
    // independent.
    std::vector<double> rowMaxOffset(size_t(sb.tilesY), 0.0);
    std::atomic<uint64_t> alphaTests{0};  // added once per chunk of rows
    const auto makeContext = [] {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        return ctx;
    };
    forEachTileRow(
        sb.tilesY, makeContext,
        [&](int ty, RTCIntersectContext& ctx) {
            double rowMax = 0.0;
            for (size_t s = size_t(ty) * size_t(sb.tilesX) * 16;
                 s < size_t(ty + 1) * size_t(sb.tilesX) * 16; ++s) {
                const size_t pixel = sb.pixelOfSlot(s);
                if (pixel == SIZE_MAX) continue;
                const int x = int(pixel % size_t(sb.width));
                const int y = sb.rowBegin + int(pixel / size_t(sb.width));  // in the image
                // The direction is the same in world and local space: the frame only translates
                // and scales uniformly.
                const glm::dvec3 wsDir = camera.generateRay(x, y).direction;
                RTCRayHit rh =
                    singleRayHit(lsEyeF, glm::vec3(wsDir), std::numeric_limits<float>::infinity());
                rtcIntersect1(accel.rtcScene(), &ctx, &rh);
                if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
                // The eye's side (the direction is the same in world and local space).
                const SurfacePoint sp = fillSurfaceSlot(sb, s, accel, rh.hit.geomID, rh.hit.primID,
                                                        rh.hit.u, rh.hit.v, -wsDir, offsetPolicy);
                sb.wsDepth[s] = float(accel.frame().wsLength(glm::length(sp.lsPoint - lsEye)));
                rowMax = std::max(rowMax, sp.lsOffset);
            }
            rowMaxOffset[size_t(ty)] = rowMax;
            if (progress) progress->advance(uint64_t(SurfaceBuffer::kTile) * uint64_t(sb.width));
        },
        [&](RTCIntersectContext&, uint64_t alphaTestsRun) { alphaTests += alphaTestsRun; });
    for (double m : rowMaxOffset) sb.lsMaxOffset = std::max(sb.lsMaxOffset, m);
    sb.alphaTests = alphaTests.load();
    return sb;
}

}  // namespace so
