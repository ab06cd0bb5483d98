#include "oracle/points.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/error.h"

namespace so {

namespace {

// A hit found for one pixel: the triangle and Embree's barycentrics on it.
struct PointHit {
    unsigned mesh = 0, prim = 0;
    float u = 0.0f, v = 0.0f;
};

// The replay channels of pixel i, if they name a triangle of this scene and a point inside it.
bool replayHit(const Scene& scene, const GBuffer& g, size_t i, PointHit& h) {
    const float m = g.meshId[i], t = g.primId[i], u = g.baryU[i], v = g.baryV[i];
    if (!(m >= 0.0f && m < float(scene.meshes.size()) && m == std::floor(m))) return false;
    const MeshPrimitive& mesh = scene.meshes[size_t(m)];
    if (!(t >= 0.0f && t < float(mesh.indices.size() / 3) && t == std::floor(t))) return false;
    if (!std::isfinite(u) || !std::isfinite(v)) return false;
    const double tol = kReplayBaryTolerance;
    if (u < -tol || v < -tol || double(u) + double(v) > 1.0 + tol) return false;
    h = {unsigned(m), unsigned(t), u, v};
    return true;
}

// The nearer surface along +n or -n from lsP within tol (local frame), or false.
bool snapHit(const Accel& accel, RTCIntersectContext& ctx, const glm::dvec3& lsP,
             const glm::dvec3& n, double tol, PointHit& h) {
    float best = std::numeric_limits<float>::infinity();
    bool found = false;
    for (double sign : {1.0, -1.0}) {
        RTCRayHit rh = singleRayHit(glm::vec3(lsP), glm::vec3(sign * n), float(tol));
        rtcIntersect1(accel.rtcScene(), &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || !(rh.ray.tfar < best)) continue;
        best = rh.ray.tfar;
        h = {rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v};
        found = true;
    }
    return found;
}

// A G-buffer a caller filled itself (not through readGBuffer) may have planes of other sizes.
void checkPlaneSizes(const GBuffer& g) {
    std::vector<std::pair<const std::vector<float>*, const char*>> planes = {
        {&g.coverage, "coverage"}, {&g.wsPX, "P.x"}, {&g.wsPY, "P.y"}, {&g.wsPZ, "P.z"},
        {&g.wsNX, "N.x"},          {&g.wsNY, "N.y"}, {&g.wsNZ, "N.z"}};
    if (g.hasReplay())
        planes.insert(planes.end(), {{&g.meshId, "id.mesh"},
                                     {&g.primId, "id.prim"},
                                     {&g.baryU, "bary.u"},
                                     {&g.baryV, "bary.v"}});
    if (!g.depth.empty()) planes.push_back({&g.depth, "Z"});
    for (const auto& [v, name] : planes)
        if (v->size() != g.pixelCount())
            throw std::invalid_argument("G-buffer: plane " + std::string(name) + " has " +
                                        std::to_string(v->size()) + " values for " +
                                        std::to_string(g.pixelCount()) + " pixels");
}

}  // namespace

double snapTolerance(const LocalFrame& frame, const glm::dvec3& wsP) {
    const double m = std::max({std::fabs(wsP.x), std::fabs(wsP.y), std::fabs(wsP.z)});
    // One float spacing at m is at most m * 2^-23.
    return kSnapLsAbs + frame.lsLength(kSnapUlps * std::ldexp(m, -23));
}

PointsSurface surfaceFromPoints(const Scene& scene, const Accel& accel, const GBuffer& g,
                                OffsetPolicy offsetPolicy) {
    checkPlaneSizes(g);
    PointsSurface out;
    out.sb = SurfaceBuffer::empty(g.width, g.height, 0);
    SurfaceBuffer& sb = out.sb;
    out.status.assign(g.pixelCount(), uint8_t(PointStatus::Background));
    const LocalFrame& frame = accel.frame();

    // Per-tile-row maxima, reduced in a fixed order afterwards: thread-count independent.
    struct RowMax {
        double offset = 0.0, snap = 0.0, tol = 0.0;
        uint64_t rejected = 0;
    };
    std::vector<RowMax> rowMax(size_t(sb.tilesY));
    std::atomic<uint64_t> alphaTests{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, sb.tilesY), [&](const tbb::blocked_range<int>& r) {
        setEmbreeFloatMode();
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        const uint64_t alphaTests0 = Accel::alphaTestsOnThisThread();
        for (int ty = r.begin(); ty != r.end(); ++ty) {
            RowMax& row = rowMax[size_t(ty)];
            for (size_t s = size_t(ty) * size_t(sb.tilesX) * 16;
                 s < size_t(ty + 1) * size_t(sb.tilesX) * 16; ++s) {
                const size_t pixel = sb.pixelOfSlot(s);
                if (pixel == SIZE_MAX || !g.covered(pixel)) continue;
                const glm::dvec3 wsP = g.wsPoint(pixel);
                const glm::dvec3 lsP = frame.lsFromWs(wsP);
                const glm::dvec3 wsN = g.wsNormal(pixel);
                const glm::dvec3 nGiven = wsN / glm::length(wsN);  // same direction in ls
                const double tol = snapTolerance(frame, wsP);
                row.tol = std::max(row.tol, tol);

                PointHit h;
                bool replayed = false;
                if (g.hasReplay() && replayHit(scene, g, pixel, h)) {
                    glm::dvec3 a, b, c;
                    accel.triangle(h.mesh, h.prim, a, b, c);
                    const double u = h.u, v = h.v;
                    const glm::dvec3 p = (1.0 - u - v) * a + u * b + v * c;
                    const double area = glm::length(glm::cross(b - a, c - a));
                    // The ids must be this scene's: the rebuilt point lies where P says.
                    replayed = area > 0.0 && glm::length(p - lsP) <= tol;
                    if (!replayed) ++row.rejected;
                }
                if (!replayed && !snapHit(accel, ctx, lsP, nGiven, tol, h)) {
                    out.status[pixel] = uint8_t(PointStatus::OffSurface);
                    continue;
                }
                out.status[pixel] =
                    uint8_t(replayed ? PointStatus::Replayed : PointStatus::Snapped);
                // As tracePrimary: the normal turned to the side the renderer shades.
                const SurfacePoint sp =
                    fillSurfaceSlot(sb, s, accel, h.mesh, h.prim, h.u, h.v, nGiven, offsetPolicy);
                sb.wsDepth[s] =
                    g.depth.empty() ? std::numeric_limits<float>::quiet_NaN() : g.depth[pixel];
                row.offset = std::max(row.offset, sp.lsOffset);
                if (!replayed) row.snap = std::max(row.snap, glm::length(sp.lsPoint - lsP));
            }
        }
        alphaTests += Accel::alphaTestsOnThisThread() - alphaTests0;
    });

    OraclePointsStats& st = out.stats;
    st.file = g.path;
    st.replayChannels = g.hasReplay();
    st.coverageChannel = g.coverageChannel;
    st.depthChannel = !g.depth.empty();
    double maxTol = 0.0, maxSnap = 0.0;
    for (const RowMax& row : rowMax) {
        sb.lsMaxOffset = std::max(sb.lsMaxOffset, row.offset);
        maxTol = std::max(maxTol, row.tol);
        maxSnap = std::max(maxSnap, row.snap);
        st.replayRejected += row.rejected;
    }
    st.wsMaxSnapTolerance = frame.wsLength(maxTol);
    st.wsMaxSnapDistance = frame.wsLength(maxSnap);
    for (uint8_t s : out.status) {
        st.background += s == uint8_t(PointStatus::Background);
        st.replayed += s == uint8_t(PointStatus::Replayed);
        st.snapped += s == uint8_t(PointStatus::Snapped);
        st.offSurface += s == uint8_t(PointStatus::OffSurface);
    }
    sb.alphaTests = alphaTests.load();
    return out;
}

nlohmann::json toJson(const OraclePointsStats& s) {
    return {{"file", s.file},
            {"coverage_channel", s.coverageChannel},
            {"replay_channels", s.replayChannels},
            {"depth_channel", s.depthChannel},
            {"pixels_replayed", s.replayed},
            {"pixels_snapped", s.snapped},
            {"pixels_off_surface", s.offSurface},
            {"pixels_background", s.background},
            {"replay_rejected", s.replayRejected},
            {"snap_tolerance",
             {{"local_abs", kSnapLsAbs},
              {"float_spacings_of_P", kSnapUlps},
              {"max_world", s.wsMaxSnapTolerance}}},
            {"max_snap_distance", s.wsMaxSnapDistance},
            {"verify_primary", "skipped: no camera in points mode; the shadow rays are re-traced"}};
}

}  // namespace so
