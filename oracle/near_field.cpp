#include "oracle/near_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/alpha_mask.h"
#include "oracle/exact_tracer.h"
#include "oracle/surface_buffer.h"

namespace so {

namespace {

struct Query {
    const Accel* accel;
    glm::dvec3 p, originNormal;
    unsigned originMesh, originPrim;
    std::vector<uint32_t>* ids;
    std::vector<NearTriangle>* triangles;
    double radius = kNearFieldRadius;
};

constexpr size_t kMaxNearField = 64;
constexpr int kMaxShrinks = 8;

// Exactly in the plane of the origin triangle (normal m0, through p): a segment leaving that
// plane on its lit side crosses such a triangle nowhere, and rounding must not make it seem to.
bool inOriginPlane(const NearTriangle& t, const glm::dvec3& m0, const glm::dvec3& p) {
    const glm::dvec3 m = glm::cross(t.b - t.a, t.c - t.a);
    return glm::length(glm::cross(m, m0)) == 0.0 && glm::dot(m, p - t.a) == 0.0;
}

// Whether an alpha-tested triangle's mask keeps the crossing at barycentrics (b1, b2): the
// coordinates interpolated in float as the mesh's Embree filter interpolates them.
bool keeps(const NearTriangle& t, double b1, double b2) {
    if (!t.alpha) return true;
    const Accel::AlphaGeometry& a = *t.alpha;
    glm::vec2 uv(0.0f);
    if (a.texture) {
        const uint32_t* i = &a.indices[3 * size_t(t.prim)];
        const float u = float(b1), v = float(b2);
        uv = (1.0f - u - v) * a.uvs[i[0]] + u * a.uvs[i[1]] + v * a.uvs[i[2]];
    }
    return alphaKeeps(*a.mask, a.texture, uv);
}

// Embree calls this for every triangle whose bounds meet the ball; the tests are in double.
bool visitCandidate(RTCPointQueryFunctionArguments* args) noexcept {
    auto& q = *static_cast<Query*>(args->userPtr);
    const unsigned mesh = args->geomID, prim = args->primID;
    if (mesh == q.originMesh && prim == q.originPrim) return false;
    NearTriangle t;
    t.alpha = q.accel->alphaGeometry(mesh);
    t.prim = prim;
    q.accel->triangle(mesh, prim, t.a, t.b, t.c);
    const glm::dvec3 m = glm::cross(t.b - t.a, t.c - t.a);
    if (!(glm::length(m) > 0.0)) return false;  // degenerate: never hit (accel.cpp leaves it out)
    if (inOriginPlane(t, q.originNormal, q.p)) return false;
    t.n = m / glm::length(m);
    t.side = glm::dot(t.n, q.p - t.a);
    if (exact::pointTriangle(q.p, t.a, t.b, t.c) > q.radius) return false;
    q.ids->push_back(q.accel->originId(mesh, prim));
    q.triangles->push_back(t);
    return false;  // the radius stays: every triangle in the ball is wanted
}

}  // namespace

bool appendNearField(const Accel& accel, const glm::dvec3& p, unsigned mesh, unsigned prim,
                     std::vector<uint32_t>& ids, std::vector<NearTriangle>& triangles) {
    glm::dvec3 a, b, c;
    accel.triangle(mesh, prim, a, b, c);
    Query q{&accel, p, glm::cross(b - a, c - a), mesh, prim, &ids, &triangles};
    const size_t before = ids.size();
    double radius = kNearFieldRadius;
    for (int shrink = 0;; ++shrink) {
        RTCPointQuery query;
        query.x = float(p.x);
        query.y = float(p.y);
        query.z = float(p.z);
        query.time = 0.0f;
        // The ball a float's rounding wider: Embree's box tests are conservative from there.
        query.radius = float(radius * (1.0 + 1e-6));
        q.radius = radius;
        RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(accel.rtcScene(), &query, &context, visitCandidate, &q);
        // A dense tangle: a smaller ball, so that no pixel holds more than the cap (each of its
        // rays tests them all); the vertex's own fan is kept whatever its size.
        if (ids.size() - before <= kMaxNearField || shrink == kMaxShrinks) return shrink > 0;
        ids.resize(before);
        triangles.resize(before);
        radius *= 0.25;
    }
}

void buildNearFields(const Accel& accel, SurfaceBuffer& sb) {
    // Per tile row, then joined in row order: the same lists at any thread count.
    struct Row {
        std::vector<uint32_t> count, ids;
        std::vector<NearTriangle> triangles;
        uint64_t shrunk = 0;
    };
    const size_t perRow = size_t(sb.tilesX) * 16;
    std::vector<Row> rows(size_t(sb.tilesY));
    tbb::parallel_for(size_t(0), rows.size(), [&](size_t ty) {
        Row& row = rows[ty];
        row.count.assign(perRow, 0);
        for (size_t k = 0; k < perRow; ++k) {
            const size_t s = ty * perRow + k;
            if (!sb.hit[s]) continue;
            const size_t before = row.ids.size();
            row.shrunk += appendNearField(accel, nearOrigin(accel, sb, s).p, sb.meshId[s],
                                          sb.primId[s], row.ids, row.triangles);
            row.count[k] = uint32_t(row.ids.size() - before);
        }
    });
    NearFields& f = sb.nearFields;
    f = {};
    f.begin.reserve(sb.slotCount() + 1);
    f.begin.push_back(0);
    for (const Row& row : rows) {
        for (uint32_t n : row.count) {
            f.begin.push_back(f.begin.back() + n);
            f.pixels += n > 0;
        }
        f.ids.insert(f.ids.end(), row.ids.begin(), row.ids.end());
        f.triangles.insert(f.triangles.end(), row.triangles.begin(), row.triangles.end());
        f.pixelsShrunk += row.shrunk;
    }
}

namespace {

// The plane distance beyond which the moved origin (offset plus its float rounding) lies on p's
// side too.
constexpr double kReach = kLsOriginOffset + 4.0 / 16777216.0;

// One segment (a hard light): T matters only where the true segment comes within the offset of
// it. Where the segment crosses T's plane at X, the moved one crosses it within kReach / |sin|
// of X, so T matters only if X is that close to T; where it does not cross, only if p is within
// kReach of the plane.
bool segmentReaches(const NearTriangle& t, const glm::dvec3& p, const NearTarget& target) {
    const glm::dvec3& n = t.n;
    const double side = t.side;
    const glm::dvec3 d = target.atInfinity ? target.direction : target.points[0] - p;  // not unit
    const double along = glm::dot(n, d);
    // The parameter of the crossing, in units of d (any t > 0 for a light at infinity).
    const double tCross = along != 0.0 ? -side / along : -1.0;
    const bool crosses = tCross > 0.0 && (target.atInfinity || tCross < 1.0);
    if (!crosses) return !(std::fabs(side) > kReach);
    const double sine = std::fabs(along) / glm::length(d);
    const glm::dvec3 x = p + tCross * d;
    const double reach = kReach * (1.0 + 1.0 / sine);
    // Outside the triangle's box by more than the reach: far (most crossings are).
    for (int k = 0; k < 3; ++k)
        if (x[k] < std::min({t.a[k], t.b[k], t.c[k]}) - reach ||
            x[k] > std::max({t.a[k], t.b[k], t.c[k]}) + reach)
            return false;
    return !(exact::pointTriangle(x, t.a, t.b, t.c) > reach);
}

}  // namespace

void appendRelevant(const NearFields& fields, uint32_t first, uint32_t last,
                    const NearOrigin& origin, const NearTarget& target, std::vector<uint32_t>& ids,
                    std::vector<NearTriangle>& triangles) {
    const bool oneSegment = target.atInfinity || target.count == 1;
    for (uint32_t i = first; i < last; ++i) {
        const NearTriangle& t = fields.triangles[i];
        bool relevant = false;
        if (oneSegment) {
            relevant = segmentReaches(t, origin.p, target);
        } else {
            // Segments to the light's points: none reaches T's plane where the whole light lies
            // on p's side of it, with p beyond the offset.
            relevant = !(std::fabs(t.side) > kReach);
            for (int k = 0; k < target.count && !relevant; ++k)
                relevant = !(t.side * glm::dot(t.n, target.points[k] - t.a) > 0.0);
        }
        if (!relevant) continue;
        ids.push_back(fields.ids[i]);
        triangles.push_back(t);
    }
}

double nearFirstHit(const uint32_t* ids, const NearTriangle* triangles, size_t n, NearList list,
                    const NearOrigin& origin, const glm::dvec3& dir, double tMax) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < n; ++i) {
        const NearTriangle& t = triangles[i];
        if (list == NearList::Tile &&
            (ids[i] == origin.id || inOriginPlane(t, origin.normal, origin.p)))
            continue;
        double tHit, b1, b2;
        if (exact::rayTriangle(origin.p, dir, 0.0, std::min(tMax, best), t.a, t.b, t.c, tHit, b1,
                               b2) &&
            keeps(t, b1, b2))
            best = tHit;
    }
    return best;
}

NearOrigin nearOrigin(const Accel& accel, const SurfaceBuffer& sb, size_t s) {
    glm::dvec3 a, b, c;
    accel.triangle(sb.meshId[s], sb.primId[s], a, b, c);
    const double u = sb.baryU[s], v = sb.baryV[s];
    return {(1.0 - u - v) * a + u * b + v * c, glm::cross(b - a, c - a), sb.originId[s]};
}

}  // namespace so
