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

// The plane distance beyond which the moved origin (offset plus its float rounding) lies on p's
// side too.
constexpr double kReach = kLsOriginOffset + 4.0 / 16777216.0;

constexpr size_t kMaxNearField = 64;
constexpr int kMaxShrinks = 3;

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

// Whether no segment from p to a point of the target's hull can make the true and the moved
// segment disagree about T (near_field.h, appendRelevant). The light's corners' heights over T's
// plane tell: all on p's side, no true segment crosses it, and none from the ray's origin either
// where that lies on the same side beyond Embree's rounding; all across, every segment crosses, at
// a sine (|n . dir|) of at least the corners' smallest height difference over their largest
// distance (the one is linear and the other convex over the hull), and such a crossing is too far
// from T to matter above the triangle's minSine (nearSineBound's argument).
bool nearRuledOut(const NearTriangle& t, const NearTarget& target, const glm::dvec3& origin,
                  double reach, double floatBand) {
    if (!(std::fabs(t.side) > 1e-12)) return false;
    bool allSame = true, allAcross = true;
    double lowestRise = std::numeric_limits<double>::infinity(), farthest = 0.0;
    for (int k = 0; k < target.count; ++k) {
        const double h = glm::dot(t.n, target.points[k] - t.a);
        allSame = allSame && h * t.side > 0.0;
        allAcross = allAcross && h * t.side < 0.0;
        lowestRise = std::min(lowestRise, std::fabs(h - t.side));
        farthest = std::max(farthest, glm::length(target.points[k] - t.p));
    }
    if (allSame) {
        const double ho = glm::dot(t.n, origin - t.a);
        return ho * t.side > 0.0 && std::fabs(ho) > floatBand;
    }
    if (!allAcross) return false;
    const double inPlane =
        exact::pointTriangle(t.p - t.side * t.n, t.a, t.b, t.c) * (1.0 - 1e-9) - 4e-16;
    if (!(inPlane > reach)) return false;
    const double minSine = (std::fabs(t.side) + reach) / (inPlane - reach);
    return lowestRise * (1.0 - 1e-9) > minSine * farthest * (1.0 + 1e-9);
}

// Embree calls this for every triangle whose bounds meet the ball; the tests are in double.
bool visitCandidate(RTCPointQueryFunctionArguments* args) noexcept {
    auto& q = *static_cast<Query*>(args->userPtr);
    const unsigned mesh = args->geomID, prim = args->primID;
    if (mesh == q.originMesh && prim == q.originPrim) return false;
    NearTriangle t;
    q.accel->triangle(mesh, prim, t.a, t.b, t.c);
    // Embree calls this for every triangle of a leaf whose box meets the ball: the triangle's own
    // box first, the cheapest test that rules most of them out.
    for (int k = 0; k < 3; ++k)
        if (std::min({t.a[k], t.b[k], t.c[k]}) > q.p[k] + q.radius ||
            std::max({t.a[k], t.b[k], t.c[k]}) < q.p[k] - q.radius)
            return false;
    const glm::dvec3 m = glm::cross(t.b - t.a, t.c - t.a);
    const double area2 = glm::length(m);
    if (!(area2 > 0.0)) return false;  // degenerate: never hit (accel.cpp leaves it out)
    t.n = m / area2;
    t.side = glm::dot(t.n, q.p - t.a);
    if (std::fabs(t.side) > q.radius) return false;  // its plane is already too far
    if (inOriginPlane(t, q.originNormal, q.p)) return false;
    if (exact::pointTriangle(q.p, t.a, t.b, t.c) > q.radius) return false;
    t.alpha = q.accel->alphaGeometry(mesh);
    t.prim = prim;
    t.p = q.p;
    q.ids->push_back(q.accel->originId(mesh, prim));
    q.triangles->push_back(t);
    return false;  // the radius stays: every triangle in the ball is wanted
}

}  // namespace

double appendNearField(const Accel& accel, const glm::dvec3& p, unsigned mesh, unsigned prim,
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
        if (ids.size() - before <= kMaxNearField || shrink == kMaxShrinks) return radius;
        ids.resize(before);
        triangles.resize(before);
        radius *= 0.25;
    }
}

float nearTnear(double radius) {
    return float((radius - 4.0 * kLsOriginOffset) * (1.0 - 1e-5));
}

float nearSineBound(const NearTriangle* triangles, size_t n, const glm::dvec3& m0,
                    const glm::dvec3& origin) {
    constexpr float kAny = std::numeric_limits<float>::infinity();
    // The reach a hair wider for its rounding; Embree's float triangle lies within kFloatBand of
    // the double one's plane (kReach less the offset).
    const double reach = kReach * (1.0 + 1e-6) + 1e-15;
    constexpr double kFloatBand = (kReach - kLsOriginOffset) * (1.0 + 1e-6);
    float bound = -kAny;
    for (size_t i = 0; i < n; ++i) {
        const NearTriangle& t = triangles[i];
        // T's normal turned towards m0, and p's and the ray origin's heights along it.
        const double sign = glm::dot(t.n, m0) < 0.0 ? -1.0 : 1.0;
        const double turn = glm::length(sign * t.n - m0);
        const double hp = sign * t.side, ho = sign * glm::dot(t.n, origin - t.a);
        double b = turn;  // both above the plane: a segment with m0 . dir > turn leaves it
        if (!(hp > 0.0 && ho > kFloatBand) && std::fabs(hp) <= 1e-12 && ho > kFloatBand) {
            // p on the plane to within rounding (a pixel on a shared edge): a segment leaving
            // at a sine over 1e-3 meets it within 1e-9 of p, contact that nearFirstHit ignores.
            b += 1e-3;
        } else if (!(hp > 0.0 && ho > kFloatBand)) {
            // p below: the true segment crosses, and must do so steeply enough to matter.
            if (!(hp < -1e-12)) return kAny;
            const double inPlane =
                exact::pointTriangle(t.p - t.side * t.n, t.a, t.b, t.c) * (1.0 - 1e-9) - 4e-16;
            if (!(inPlane > reach)) return kAny;
            b += (std::fabs(t.side) + reach) / (inPlane - reach);
        }
        b = b * (1.0 + 1e-6) + 1e-7;
        if (!(b < 1.0)) return kAny;  // no unit direction rules it out
        bound = std::max(bound, float(b) * (1.0f + 1e-6f));
    }
    return bound;
}

void buildNearFields(const Accel& accel, SurfaceBuffer& sb) {
    // Per tile row, then joined in row order: the same lists at any thread count.
    struct Row {
        std::vector<uint32_t> count, ids;
        std::vector<float> tnear, sineBound;
        std::vector<NearTriangle> triangles;
        uint64_t shrunk = 0;
    };
    const size_t perRow = size_t(sb.tilesX) * 16;
    std::vector<Row> rows(size_t(sb.tilesY));
    tbb::parallel_for(size_t(0), rows.size(), [&](size_t ty) {
        Row& row = rows[ty];
        row.count.assign(perRow, 0);
        row.tnear.assign(perRow, 0.0f);
        row.sineBound.assign(perRow, -std::numeric_limits<float>::infinity());
        for (size_t k = 0; k < perRow; ++k) {
            const size_t s = ty * perRow + k;
            if (!sb.hit[s]) continue;
            const size_t before = row.ids.size();
            const double radius = appendNearField(accel, nearPoint(accel, sb, s), sb.meshId[s],
                                                  sb.primId[s], row.ids, row.triangles);
            row.shrunk += radius < kNearFieldRadius;
            row.count[k] = uint32_t(row.ids.size() - before);
            row.tnear[k] = nearTnear(radius);
            if (row.count[k] == 0) continue;
            glm::dvec3 a, b, c;
            accel.triangle(sb.meshId[s], sb.primId[s], a, b, c);
            glm::dvec3 m0 = glm::normalize(glm::cross(b - a, c - a));
            if (glm::dot(m0, glm::dvec3(sb.lsNormal(s))) < 0.0) m0 = -m0;  // the lit side's
            row.sineBound[k] = nearSineBound(&row.triangles[before], row.count[k], m0,
                                             glm::dvec3(sb.lsRayOrigin(s)));
        }
    });
    NearFields& f = sb.nearFields;
    f = {};
    size_t total = 0;
    for (const Row& row : rows) total += row.triangles.size();
    f.begin.reserve(sb.slotCount() + 1);
    f.ids.reserve(total);
    f.triangles.reserve(total);
    f.tnear.reserve(sb.slotCount());
    f.sineBound.reserve(sb.slotCount());
    f.begin.push_back(0);
    for (const Row& row : rows) {
        for (uint32_t n : row.count) {
            f.begin.push_back(f.begin.back() + n);
            f.pixels += n > 0;
        }
        f.ids.insert(f.ids.end(), row.ids.begin(), row.ids.end());
        f.triangles.insert(f.triangles.end(), row.triangles.begin(), row.triangles.end());
        f.tnear.insert(f.tnear.end(), row.tnear.begin(), row.tnear.end());
        f.sineBound.insert(f.sineBound.end(), row.sineBound.begin(), row.sineBound.end());
        f.pixelsShrunk += row.shrunk;
    }
    f.tileSineBound.assign(sb.slotCount() / 16, -std::numeric_limits<float>::infinity());
    for (size_t s = 0; s < f.sineBound.size(); ++s) {
        f.tileSineBound[s / 16] = std::max(f.tileSineBound[s / 16], f.sineBound[s]);
        f.pixelsUnbounded += std::isinf(f.sineBound[s]) && f.sineBound[s] > 0.0f;
    }
    for (float b : f.tileSineBound) f.tilesUnbounded += std::isinf(b) && b > 0.0f;
}

void appendRelevant(const NearFields& fields, uint32_t first, uint32_t last,
                    const NearTarget& target, const glm::dvec3& origin, std::vector<uint32_t>& ids,
                    std::vector<NearTriangle>& triangles) {
    const double reach = kReach * (1.0 + 1e-6) + 1e-15;
    constexpr double kFloatBand = (kReach - kLsOriginOffset) * (1.0 + 1e-6);
    for (uint32_t i = first; i < last; ++i) {
        const NearTriangle& t = fields.triangles[i];
        if (!nearRuledOut(t, target, origin, reach, kFloatBand)) {
            ids.push_back(fields.ids[i]);
            triangles.push_back(t);
        }
    }
}

namespace {

// Whether x, a point of T's plane up to rounding, lies outside one of T's edges' lines by more
// than 1e-12 local units: n x edge points into T and has the edge's length (n is T's own unit
// normal), so (n x edge) . (x - from) is the signed distance times |edge|, compared squared.
bool clearlyOutside(const NearTriangle& t, const glm::dvec3& x) {
    const glm::dvec3* v[3] = {&t.a, &t.b, &t.c};
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 edge = *v[(i + 1) % 3] - *v[i];
        const double inside = glm::dot(glm::cross(t.n, edge), x - *v[i]);
        if (inside < 0.0 && inside * inside > 1e-24 * glm::dot(edge, edge)) return true;
    }
    return false;
}

}  // namespace

double nearFirstHit(const NearTriangle* triangles, size_t n, const glm::dvec3& dir, double tMax) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < n; ++i) {
        const NearTriangle& t = triangles[i];
        // A segment heading away from T's plane, or reaching it only beyond its end, crosses T
        // nowhere: most near triangles, ruled out before the exact test. side and along carry
        // rounding far under the margins (|p|, |n|, |dir| ~ 1). Where p lies on the plane to
        // within that rounding (a pixel on a shared edge), whether it starts above or below is
        // the rounding's, and so is either answer; the sign computed here decides.
        const double along = glm::dot(t.n, dir);
        // Meeting the plane within kNearContact of p: T touches the receiver at its point.
        if (std::fabs(t.side) <= kNearContact * std::fabs(along)) continue;
        const double reach = std::min(tMax, best) * std::fabs(along) * (1.0 + 1e-9) + 1e-12;
        if (t.side * along > 0.0 || (t.side == 0.0 && along != 0.0)) continue;
        if (std::fabs(t.side) > 1e-12) {
            if (along == 0.0 || std::fabs(t.side) > reach) continue;
            // It crosses the plane at x: outside an edge's line by far more than x's rounding
            // (its coordinates are ~1), it crosses T nowhere (the neighbour across a ridge).
            if (clearlyOutside(t, t.p - (t.side / along) * dir)) continue;
        }
        double tHit, b1, b2;
        if (exact::rayTriangle(t.p, dir, 0.0, std::min(tMax, best), t.a, t.b, t.c, tHit, b1, b2) &&
            keeps(t, b1, b2))
            best = tHit;
    }
    return best;
}

glm::dvec3 nearPoint(const Accel& accel, const SurfaceBuffer& sb, size_t s) {
    glm::dvec3 a, b, c;
    accel.triangle(sb.meshId[s], sb.primId[s], a, b, c);
    const double u = sb.baryU[s], v = sb.baryV[s];
    return (1.0 - u - v) * a + u * b + v * c;
}

}  // namespace so
