#include "oracle/occluder_union.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace so {

namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;
using glm::dvec3;

// Which side of triangle abc's plane p lies on: +1 in front (where its normal points), -1 behind,
// 0 in the plane to rounding (its projection through p is then a segment, of no area).
int sideOf(const dvec3& p, const dvec3& a, const dvec3& b, const dvec3& c) {
    const dvec3 normal = glm::cross(b - a, c - a);
    const double scale =
        glm::length(normal) * (glm::length(p - a) + glm::length(p - b) + glm::length(p - c));
    const double side = glm::dot(normal, p - a);
    return std::abs(side) <= 1e-13 * scale ? 0 : side > 0.0 ? 1 : -1;
}

// Whether `facing` leaves triangle id out for a point on `side` of it.
bool backFace(const MeshFacing* facing, TriangleId id, int side) {
    if (!facing || id.mesh >= facing->size()) return false;
    const std::vector<int8_t>& keep = (*facing)[id.mesh];
    return id.prim < keep.size() && keep[id.prim] != 0 && keep[id.prim] != side;
}

// The shadow triangle abc casts on the light from p: clipped to the pyramid, projected centrally
// through p onto the light's plane (every point of the clipped part lies between p and the plane,
// so dot(emitNormal, q - p) is in [-height, 0)). Empty where nothing is left. `whole`: no
// half-space cut the triangle, so the shadow's vertices are the projections of a, b and c, in
// that order.
SmallPolygon shadowOf(const dvec3& a, const dvec3& b, const dvec3& c, const OccluderQuery& q,
                      bool& whole) {
    SmallPolygon part{a, b, c};
    whole = true;
    for (const ExactTracer::HalfSpace& h : *q.pyramid) {
        if (glm::dot(h.normal, a) <= h.offset && glm::dot(h.normal, b) <= h.offset &&
            glm::dot(h.normal, c) <= h.offset)
            continue;  // clipToHalfSpace would keep the polygon as it is
        whole = false;
        part = clipToHalfSpace(part, h);
        if (part.n < 3) return SmallPolygon{};
    }
    for (dvec3& y : part) {
        const double along = glm::dot(q.frame->emitNormal, y - q.p);
        if (!(along < 0.0)) return SmallPolygon{};  // at p itself: only a triangle through p
        y = q.p + (y - q.p) * (-q.height / along);
    }
    return part;
}

// Twice the signed area of the triangle abc: > 0 where c lies left of a -> b. Every shadow lies in
// the visible light, so coordinates are in [0, 2^29] up to rounding and the products fit in 64
// bits exactly.
cInt turn(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
    return (b.X - a.X) * (c.Y - a.Y) - (b.Y - a.Y) * (c.X - a.X);
}

// Whether the counter-clockwise `shadow` is a convex polygon of positive area wound once, and
// holds every vertex of `lit` (inside or on its boundary): then it holds lit, a polygon of those
// vertices. Rounding may leave repeated vertices, collinear runs or, for a tiny shadow, no area or
// a fold: those are refused (the union decides them).
bool holds(const IntPoint* shadow, size_t count, const Path& lit) {
    std::array<IntPoint, SmallPolygon::kCapacity> v;
    size_t n = 0;
    for (size_t i = 0; i < count; ++i)
        if (n == 0 || !(shadow[i] == v[n - 1])) v[n++] = shadow[i];
    while (n > 1 && v[0] == v[n - 1]) --n;
    if (n < 3) return false;
    int xChanges = 0, yChanges = 0, xSign = 0, ySign = 0;
    bool turns = false;
    for (size_t i = 0; i < n; ++i) {
        const IntPoint &a = v[i], &b = v[(i + 1) % n], &c = v[(i + 2) % n];
        const cInt t = turn(a, b, c);
        const cInt along = (b.X - a.X) * (c.X - b.X) + (b.Y - a.Y) * (c.Y - b.Y);
        if (t < 0 || (t == 0 && along < 0)) return false;  // a right turn, or a fold back
        turns |= t > 0;
        // A convex polygon wound once: its edges' x (and y) directions change sign twice.
        const int sx = (b.X > a.X) - (b.X < a.X), sy = (b.Y > a.Y) - (b.Y < a.Y);
        if (sx != 0) xChanges += xSign != 0 && sx != xSign, xSign = sx;
        if (sy != 0) yChanges += ySign != 0 && sy != ySign, ySign = sy;
    }
    if (!turns || xChanges > 2 || yChanges > 2) return false;
    for (const IntPoint& y : lit)
        for (size_t i = 0; i < n; ++i)
            if (turn(v[i], v[(i + 1) % n], y) < 0) return false;
    return true;
}

bool lessPoint(const IntPoint& a, const IntPoint& b) {
    return a.X < b.X || (a.X == b.X && a.Y < b.Y);
}

// The union of counter-clockwise triangles as the loops of their edges that no neighbour cancels
// (issue 45, "merge a mesh's adjacent projections"). Under non-zero filling a set of paths covers
// the points its winding number is not 0 at, and the winding number of a sum of cycles is the sum
// of theirs: the triangles' edges, less the pairs that run the same segment both ways, still form
// cycles whose winding number at every point is the count of triangles over it, so they fill
// exactly the triangles' union. Two neighbours' shared edge cancels where their vertices quantised
// to the same integers (the same double vertices give the same ones), which leaves Clipper a
// patch's outline instead of every triangle in it.
void appendMergedLoops(const std::vector<std::array<IntPoint, 3>>& triangles, Paths& out) {
    struct Edge {
        IntPoint lo, hi;
        bool forward;  // runs lo -> hi
    };
    std::vector<Edge> edges;
    edges.reserve(3 * triangles.size());
    for (const std::array<IntPoint, 3>& t : triangles)
        for (size_t k = 0; k < 3; ++k) {
            const IntPoint &a = t[k], &b = t[(k + 1) % 3];
            const bool forward = lessPoint(a, b);
            edges.push_back({forward ? a : b, forward ? b : a, forward});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        if (!(x.lo == y.lo)) return lessPoint(x.lo, y.lo);
        if (!(x.hi == y.hi)) return lessPoint(x.hi, y.hi);
        return x.forward < y.forward;
    });
    // Per segment: as many runs as one way exceeds the other, from -> to.
    std::vector<std::pair<IntPoint, IntPoint>> kept;
    for (size_t e = 0; e < edges.size();) {
        size_t end = e, forward = 0;
        while (end < edges.size() && edges[end].lo == edges[e].lo && edges[end].hi == edges[e].hi)
            forward += edges[end++].forward;
        const size_t backward = end - e - forward;
        for (size_t k = std::min(forward, backward); k < std::max(forward, backward); ++k)
            kept.push_back(forward > backward ? std::pair{edges[e].lo, edges[e].hi}
                                              : std::pair{edges[e].hi, edges[e].lo});
        e = end;
    }
    std::sort(kept.begin(), kept.end(), [](const auto& x, const auto& y) {
        return lessPoint(x.first, y.first) || (x.first == y.first && lessPoint(x.second, y.second));
    });
    // Every point has as many kept runs in as out: walking from a run's start always returns.
    std::vector<uint8_t> used(kept.size(), 0);
    for (size_t i = 0; i < kept.size(); ++i) {
        if (used[i]) continue;
        Path loop;
        const IntPoint start = kept[i].first;
        for (size_t cur = i;;) {
            used[cur] = 1;
            loop.push_back(kept[cur].first);
            const IntPoint next = kept[cur].second;
            if (next == start) break;
            auto it = std::lower_bound(
                kept.begin(), kept.end(), next,
                [](const auto& edge, const IntPoint& q) { return lessPoint(edge.first, q); });
            size_t k = size_t(it - kept.begin());
            while (k < kept.size() && kept[k].first == next && used[k]) ++k;
            SO_CHECK(k < kept.size() && kept[k].first == next);
            cur = k;
        }
        out.push_back(std::move(loop));
    }
}

template <typename Polygon>
Path quantisedPath(const LightPlaneFrame& frame, const Polygon& poly) {
    Path out;
    out.reserve(poly.size());
    for (const dvec3& y : poly) out.push_back(frame.quantised(y));
    if (!ClipperLib::Orientation(out)) ClipperLib::ReversePath(out);  // all windings alike
    return out;
}

}  // namespace

LightPlaneFrame::LightPlaneFrame(const dvec3& origin_, const dvec3& edgeU_, const dvec3& edgeV_,
                                 const dvec3& emitNormal_)
    : origin(origin_),
      edgeU(edgeU_),
      edgeV(edgeV_),
      emitNormal(emitNormal_),
      invUU(1.0 / glm::dot(edgeU_, edgeU_)),
      invVV(1.0 / glm::dot(edgeV_, edgeV_)) {}

IntPoint LightPlaneFrame::quantised(const dvec3& y) const {
    const dvec3 d = y - origin;
    return {cInt(std::llround(glm::dot(d, edgeU) * invUU * kQuantum)),
            cInt(std::llround(glm::dot(d, edgeV) * invVV * kQuantum))};
}

dvec3 LightPlaneFrame::point(const IntPoint& q) const {
    return origin + (double(q.X) / kQuantum) * edgeU + (double(q.Y) / kQuantum) * edgeV;
}

Path LightPlaneFrame::path(const SmallPolygon& poly) const {
    return quantisedPath(*this, poly);
}

Path LightPlaneFrame::path(const std::vector<dvec3>& poly) const {
    return quantisedPath(*this, poly);
}

Paths lightMinusShadows(const Path& light, const Paths& shadows) {
    ClipperLib::Clipper clipper;
    clipper.AddPath(light, ClipperLib::ptSubject, true);
    clipper.AddPaths(shadows, ClipperLib::ptClip, true);
    Paths visible;
    clipper.Execute(ClipperLib::ctDifference, visible, ClipperLib::pftNonZero,
                    ClipperLib::pftNonZero);
    return visible;
}

namespace {

// The shadows met so far: polygons, and whole triangles kept apart to be merged.
struct Shadows {
    Paths polygons;
    std::vector<std::array<IntPoint, 3>> triangles;
    bool empty() const { return polygons.empty() && triangles.empty(); }
    Paths all() const {
        Paths out = polygons;
        appendMergedLoops(triangles, out);
        return out;
    }
};

// Adds one shadow (the projected part of a triangle); returns whether it alone holds lit.
bool addShadow(const SmallPolygon& shadow, bool whole, const OccluderQuery& q, Shadows& into) {
    if (whole && q.options.merge) {
        std::array<IntPoint, 3> t{q.frame->quantised(shadow.v[0]), q.frame->quantised(shadow.v[1]),
                                  q.frame->quantised(shadow.v[2])};
        const cInt area = turn(t[0], t[1], t[2]);
        if (area == 0) return false;  // no area: covers nothing
        if (area < 0) std::swap(t[1], t[2]);
        into.triangles.push_back(t);
        return q.options.shortcuts && holds(t.data(), 3, *q.lit);
    }
    into.polygons.push_back(q.frame->path(shadow));
    const Path& path = into.polygons.back();
    return q.options.shortcuts && holds(path.data(), path.size(), *q.lit);
}

}  // namespace

OccluderUnion gatherShadows(const ExactTracer& tracer, const OccluderQuery& q) {
    OccluderUnion u;
    Shadows shadows;
    uint32_t nextCheck = 4;
    bool capped = false, alpha = false, covered = false;
    const auto visit = [&](const dvec3& a, const dvec3& b, const dvec3& c, TriangleId id) {
        if (++u.candidates > q.maxCandidates) {
            capped = true;
            return false;
        }
        if (id == q.self) return true;
        const int side = sideOf(q.p, a, b, c);
        if (side == 0) return true;
        if (backFace(q.options.facing, id, side)) {
            ++u.backFaces;
            return true;
        }
        bool whole = false;
        const SmallPolygon shadow = shadowOf(a, b, c, q, whole);
        if (shadow.n < 3) return true;
        if (tracer.alphaTested(id)) {
            alpha = true;
            return false;
        }
        ++u.occluders;
        covered = addShadow(shadow, whole, q, shadows);
        if (q.options.shortcuts && !covered && u.occluders == nextCheck) {
            nextCheck *= 4;
            ++u.unions;
            covered = lightMinusShadows(*q.lit, shadows.all()).empty();
        }
        return !covered;
    };
    tracer.forEachTriangleIn(*q.pyramid, visit);
    if (capped || alpha) {
        u.status =
            capped ? OccluderUnion::Status::TooManyOccluders : OccluderUnion::Status::AlphaTested;
        return u;
    }
    if (covered) {
        u.status = OccluderUnion::Status::Covered;
        return u;
    }
    if (shadows.empty() && q.options.shortcuts) {
        u.status = OccluderUnion::Status::Lit;
        return u;
    }
    u.shadows = shadows.all();
    return u;
}

}  // namespace so
