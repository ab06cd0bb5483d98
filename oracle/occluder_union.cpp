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
    const double side = glm::dot(normal, p - a);
    // The tolerance is 1e-13 |normal| (|p - a| + |p - b| + |p - c|); its square is at most
    // 3e-26 |normal|^2 (the squared lengths' sum), which needs no square root: most triangles
    // are decided by that bound alone.
    const double n2 = glm::dot(normal, normal);
    const double l2 = glm::dot(p - a, p - a) + glm::dot(p - b, p - b) + glm::dot(p - c, p - c);
    if (side * side > 3e-26 * n2 * l2) return side > 0.0 ? 1 : -1;
    const double scale =
        std::sqrt(n2) * (glm::length(p - a) + glm::length(p - b) + glm::length(p - c));
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

// The slab's shortcut (issue 45, "project only silhouette loops"): a triangle wholly between p's
// level and the light's plane (dot(emitNormal, y - p) in [-height, 0) at its three vertices)
// casts, through p, the projection of the whole triangle, and the part of that projection inside
// the visible light is exactly the shadow of the triangle clipped to the pyramid (the pyramid is
// the set of points of the slab whose projection lands in the light), so the union inside the
// light is the same without clipping. Its quantised vertices, where they lie within
// kWholeMargin of the frame's unit square (so that the integer products below stay exact); else
// false, and the triangle is clipped.
constexpr double kWholeMargin = 0.5;
bool projectWhole(const dvec3& a, const dvec3& b, const dvec3& c, const OccluderQuery& q,
                  std::array<IntPoint, 3>& out) {
    const ExactTracer::HalfSpace& plane = q.pyramid->back();  // the light's plane, p's side
    const LightPlaneFrame& f = *q.frame;
    const std::array<const dvec3*, 3> v{&a, &b, &c};
    for (size_t k = 0; k < 3; ++k) {
        const dvec3& y = *v[k];
        const double along = glm::dot(f.emitNormal, y - q.p);
        if (!(along < 0.0) || glm::dot(plane.normal, y) > plane.offset) return false;
        const dvec3 d = q.p + (y - q.p) * (-q.height / along) - f.origin;
        const double s = glm::dot(d, f.edgeU) * f.invUU, t = glm::dot(d, f.edgeV) * f.invVV;
        if (!(std::abs(s - 0.5) <= 0.5 + kWholeMargin && std::abs(t - 0.5) <= 0.5 + kWholeMargin))
            return false;
        out[k] = {cInt(std::llround(s * LightPlaneFrame::kQuantum)),
                  cInt(std::llround(t * LightPlaneFrame::kQuantum))};
    }
    return true;
}

// Twice the signed area of the triangle abc: > 0 where c lies left of a -> b. Every shadow's
// coordinates are within kWholeMargin of the frame's square, [-2^28, 3 2^28] up to rounding, so
// the differences are below 2^30 and the products fit in 64 bits exactly.
cInt turn(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
    return (b.X - a.X) * (c.Y - a.Y) - (b.Y - a.Y) * (c.X - a.X);
}

// Whether `v` (count points) is a convex polygon of positive area wound once counter-clockwise;
// `n` its vertices without repeats (into v's front). Rounding may leave repeated vertices,
// collinear runs or, for a tiny shadow, no area or a fold: those are refused.
bool convexCounterClockwise(IntPoint* v, size_t count, size_t& n) {
    n = 0;
    for (size_t i = 0; i < count; ++i)
        if (n == 0 || !(v[i] == v[n - 1])) v[n++] = v[i];
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
    return turns && xChanges <= 2 && yChanges <= 2;
}

// Whether the counter-clockwise `shadow` is a convex polygon of positive area wound once, and
// holds every vertex of `lit` (inside or on its boundary): then it holds lit, a polygon of those
// vertices.
bool holds(const IntPoint* shadow, size_t count, const Path& lit) {
    std::array<IntPoint, SmallPolygon::kCapacity> v;
    std::copy(shadow, shadow + count, v.begin());
    size_t n = 0;
    if (!convexCounterClockwise(v.data(), count, n)) return false;
    for (const IntPoint& y : lit)
        for (size_t i = 0; i < n; ++i)
            if (turn(v[i], v[(i + 1) % n], y) < 0) return false;
    return true;
}

// holds() for a counter-clockwise triangle of positive area (convex, wound once).
bool triangleHolds(const std::array<IntPoint, 3>& t, const Path& lit) {
    for (const IntPoint& y : lit)
        for (size_t k = 0; k < 3; ++k)
            if (turn(t[k], t[(k + 1) % 3], y) < 0) return false;
    return true;
}

// Whether the closed segment ab keeps out of the open interior of the convex counter-clockwise
// polygon `lit`: a line through an edge of lit, or through ab, has them on its two closed sides
// (two convex sets with disjoint interiors are separated along one of their edges' directions).
bool separated(const IntPoint& a, const IntPoint& b, const Path& lit) {
    const size_t n = lit.size();
    for (size_t i = 0; i < n; ++i)
        if (turn(lit[i], lit[(i + 1) % n], a) <= 0 && turn(lit[i], lit[(i + 1) % n], b) <= 0)
            return true;
    bool left = false, right = false;
    for (const IntPoint& y : lit) {
        const cInt t = turn(a, b, y);
        left |= t > 0, right |= t < 0;
    }
    return !(left && right);
}

// Whether the counter-clockwise triangle t keeps out of lit's open interior.
bool separated(const std::array<IntPoint, 3>& t, const Path& lit) {
    const size_t n = lit.size();
    for (size_t i = 0; i < n; ++i) {
        bool out = true;
        for (const IntPoint& y : t) out = out && turn(lit[i], lit[(i + 1) % n], y) <= 0;
        if (out) return true;
    }
    for (size_t k = 0; k < 3; ++k) {
        bool out = true;
        for (const IntPoint& y : lit) out = out && turn(t[k], t[(k + 1) % 3], y) <= 0;
        if (out) return true;
    }
    return false;
}

// The winding number about c of the directed edge a -> b (crossings of the ray from c towards +x).
int windingOf(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
    if (a.Y <= c.Y && b.Y > c.Y && turn(a, b, c) > 0) return 1;
    if (b.Y <= c.Y && a.Y > c.Y && turn(a, b, c) < 0) return -1;
    return 0;
}

bool lessPoint(const IntPoint& a, const IntPoint& b) {
    return a.X < b.X || (a.X == b.X && a.Y < b.Y);
}

uint32_t root(std::vector<uint32_t>& parent, uint32_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
}

// The union of counter-clockwise triangles as their edges that no neighbour cancels (issue 45,
// "merge a mesh's adjacent projections"). Under non-zero filling a set of paths covers the points
// its winding number is not 0 at, and the winding number of a sum of cycles is the sum of theirs:
// the triangles' edges, less the pairs that run the same segment both ways, still form cycles
// whose winding number at every point is the count of triangles over it, so they fill exactly the
// triangles' union. Two neighbours' shared edge cancels where their vertices quantised to the
// same integers (the same double vertices give the same ones), which leaves Clipper a patch's
// outline instead of every triangle in it.
//
// Each kept edge also names its part: the triangles joined through the segments they share. A
// part's kept edges are cycles too, of winding number the count of the part's triangles over a
// point (>= 0), and the parts' numbers add up to the whole's.
struct MergedEdge {
    IntPoint from, to;
    uint32_t part;
};
// A point as one sortable key: x then y, both biased to be non-negative (every coordinate here is
// within [-2^28, 3 2^28] up to rounding: turn()).
uint64_t keyOf(const IntPoint& a) {
    constexpr cInt kBias = cInt(1) << 30;
    return (uint64_t(a.X + kBias) << 32) | uint64_t(a.Y + kBias);
}

IntPoint pointOf(uint64_t key) {
    constexpr cInt kBias = cInt(1) << 30;
    return {cInt(key >> 32) - kBias, cInt(key & 0xffffffffu) - kBias};
}

// The segments met, in an open-addressing table (linear probing; its order, and so the kept
// edges', depends only on the triangles and their order: the same at any thread count).
void mergeEdges(const std::vector<std::array<IntPoint, 3>>& triangles,
                std::vector<MergedEdge>& kept) {
    struct Segment {
        uint64_t lo = 0, hi = 0;  // keyOf its ends, lo < hi; hi 0: an empty slot (lo < hi)
        int32_t net = 0;          // runs lo -> hi less runs hi -> lo
        uint32_t triangle = 0;    // the first to run it
    };
    size_t capacity = 16;
    while (capacity < 6 * triangles.size()) capacity *= 2;
    std::vector<Segment> table(capacity);
    std::vector<uint32_t> parent(triangles.size());
    for (uint32_t t = 0; t < parent.size(); ++t) parent[t] = t;
    for (size_t i = 0; i < triangles.size(); ++i)
        for (size_t k = 0; k < 3; ++k) {
            const uint64_t a = keyOf(triangles[i][k]), b = keyOf(triangles[i][(k + 1) % 3]);
            const uint64_t lo = std::min(a, b), hi = std::max(a, b);
            size_t slot = size_t((lo * 0x9E3779B97F4A7C15ull) ^ (hi * 0xC2B2AE3D27D4EB4Full)) >> 7;
            for (slot &= capacity - 1;; slot = (slot + 1) & (capacity - 1)) {
                Segment& seg = table[slot];
                if (seg.hi == 0) seg = {lo, hi, 0, uint32_t(i)};
                if (seg.lo != lo || seg.hi != hi) continue;
                seg.net += a < b ? 1 : -1;
                parent[root(parent, uint32_t(i))] = root(parent, seg.triangle);
                break;
            }
        }
    kept.clear();
    // Per segment: as many runs as one way exceeds the other, from -> to.
    for (const Segment& seg : table) {
        if (seg.net == 0) continue;
        const IntPoint lo = pointOf(seg.lo), hi = pointOf(seg.hi);
        const uint32_t part = root(parent, seg.triangle);
        for (int32_t k = 0; k < std::abs(seg.net); ++k)
            kept.push_back(seg.net > 0 ? MergedEdge{lo, hi, part} : MergedEdge{hi, lo, part});
    }
}

// The kept edges as closed loops, appended to `out`.
void appendLoops(std::vector<MergedEdge> kept, Paths& out) {
    std::sort(kept.begin(), kept.end(), [](const MergedEdge& x, const MergedEdge& y) {
        return lessPoint(x.from, y.from) || (x.from == y.from && lessPoint(x.to, y.to));
    });
    // Every point has as many kept runs in as out: walking from a run's start always returns.
    std::vector<uint8_t> used(kept.size(), 0);
    for (size_t i = 0; i < kept.size(); ++i) {
        if (used[i]) continue;
        Path loop;
        const IntPoint start = kept[i].from;
        for (size_t cur = i;;) {
            used[cur] = 1;
            loop.push_back(kept[cur].from);
            const IntPoint next = kept[cur].to;
            if (next == start) break;
            auto it = std::lower_bound(
                kept.begin(), kept.end(), next,
                [](const MergedEdge& edge, const IntPoint& q) { return lessPoint(edge.from, q); });
            size_t k = size_t(it - kept.begin());
            while (k < kept.size() && kept[k].from == next && used[k]) ++k;
            SO_CHECK(k < kept.size() && kept[k].from == next);
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

// The covered shortcut without Clipper: whether the union of the shadows (`kept`, the merged edges
// of the whole triangles, and `polygons`) holds the convex counter-clockwise `lit`. Every part (a
// set of triangles joined through shared segments, mergeEdges) and every polygon has a winding
// number >= 0 everywhere, and those whose edges all keep out of lit's open interior have a
// constant one there, read at one point c inside it. If those constants add up to at least 1,
// the winding number of all the shadows is at least 1 all over lit: the plain union (non-zero
// filling) holds lit, and more shadows can only add to it. A polygon that crosses lit and is not
// convex and counter-clockwise (a fold left by rounding) could subtract: then no answer (false).
bool coversLit(const std::vector<MergedEdge>& kept, size_t triangles, const Paths& polygons,
               const Path& lit) {
    const size_t n = lit.size();
    cInt sx = 0, sy = 0;
    for (const IntPoint& y : lit) sx += y.X, sy += y.Y;
    const IntPoint c{sx / cInt(n), sy / cInt(n)};
    for (size_t i = 0; i < n; ++i)
        if (turn(lit[i], lit[(i + 1) % n], c) <= 0) return false;  // a sliver: no inner point
    std::vector<int> winding(triangles, 0);
    std::vector<uint8_t> crosses(triangles, 0);
    for (const MergedEdge& e : kept) {
        if (!separated(e.from, e.to, lit))
            crosses[e.part] = 1;
        else
            winding[e.part] += windingOf(e.from, e.to, c);
    }
    long total = 0;
    for (size_t t = 0; t < triangles; ++t) total += crosses[t] ? 0 : winding[t];
    for (const Path& path : polygons) {
        int w = 0;
        bool inside = false;
        for (size_t i = 0; i < path.size() && !inside; ++i) {
            const IntPoint &a = path[i], &b = path[(i + 1) % path.size()];
            inside = !separated(a, b, lit);
            w += windingOf(a, b, c);
        }
        if (!inside) {
            total += w;
            continue;
        }
        std::array<IntPoint, SmallPolygon::kCapacity> v;
        size_t m = 0;
        if (path.size() > v.size()) return false;
        std::copy(path.begin(), path.end(), v.begin());
        if (!convexCounterClockwise(v.data(), path.size(), m)) return false;
    }
    return total >= 1;
}

// The shadows met so far: polygons, and whole triangles kept apart to be merged.
struct Shadows {
    Paths polygons;
    std::vector<std::array<IntPoint, 3>> triangles;
    std::vector<MergedEdge> kept;  // the triangles' merged edges, after merge()
    bool empty() const { return polygons.empty() && triangles.empty(); }
    void merge() { mergeEdges(triangles, kept); }
    // After merge(): with `lit` convex (litConvex).
    bool cover(const Path& lit) const { return coversLit(kept, triangles.size(), polygons, lit); }
    // After merge(): every shadow, as paths whose non-zero filling is their union.
    Paths paths() {
        Paths out = std::move(polygons);
        appendLoops(kept, out);
        return out;
    }
};

// What the query holds fixed: lit and whether it is convex (a quantised sliver may not be; the
// tests on lit's edges then keep quiet).
struct LitRegion {
    const Path& path;
    bool convex;
};

bool isConvex(const Path& lit) {
    std::array<IntPoint, SmallPolygon::kCapacity> v;
    size_t n = 0;
    if (lit.size() > v.size()) return false;
    std::copy(lit.begin(), lit.end(), v.begin());
    return convexCounterClockwise(v.data(), lit.size(), n) && n == lit.size();
}

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

// The slab's whole triangle t (projectWhole) wound counter-clockwise; false where it has no area
// or keeps out of lit's interior (it covers nothing there).
bool orientWhole(std::array<IntPoint, 3>& t, const LitRegion& lit) {
    const cInt area = turn(t[0], t[1], t[2]);
    if (area == 0) return false;
    if (area < 0) std::swap(t[1], t[2]);
    return !(lit.convex && separated(t, lit.path));
}

}  // namespace

// The covered checks before the last: at 64, 512, 4,096 ... shadows. Each merges every shadow met
// so far, so at this growth they cost at most a seventh of the last one; the shadows of a
// tessellated occluder cover the light only once the whole patch is in, which the BVH's order
// rarely brings early (the bunny: checks at 8, 16, 32 ... stopped no query earlier and cost 30%).
constexpr uint32_t kFirstCheck = 64, kCheckGrowth = 8;

OccluderUnion gatherShadows(const ExactTracer& tracer, const OccluderQuery& q) {
    OccluderUnion u;
    Shadows shadows;
    const LitRegion lit{*q.lit, isConvex(*q.lit)};
    const bool checks = q.options.shortcuts && lit.convex;
    uint32_t nextCheck = kFirstCheck, lastCheck = 0;  // lastCheck: the shadows' count then
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
        std::array<IntPoint, 3> t;
        const bool slab = q.options.merge && projectWhole(a, b, c, q, t);
        bool whole = false;
        const SmallPolygon shadow = slab ? SmallPolygon{} : shadowOf(a, b, c, q, whole);
        if (slab ? !orientWhole(t, lit) : shadow.n < 3) return true;
        if (tracer.alphaTested(id)) {
            alpha = true;
            return false;
        }
        ++u.occluders;
        if (slab) {
            shadows.triangles.push_back(t);
            covered = q.options.shortcuts && triangleHolds(t, *q.lit);
        } else {
            covered = addShadow(shadow, whole, q, shadows);
        }
        if (checks && !covered && u.occluders == nextCheck) {
            nextCheck *= kCheckGrowth;
            lastCheck = u.occluders;
            ++u.coverChecks;
            shadows.merge();
            covered = shadows.cover(*q.lit);
        }
        return !covered;
    };
    tracer.forEachTriangleIn(*q.pyramid, visit);
    if (capped || alpha) {
        u.status =
            capped ? OccluderUnion::Status::TooManyOccluders : OccluderUnion::Status::AlphaTested;
        return u;
    }
    if (!covered && shadows.empty() && q.options.shortcuts) {
        u.status = OccluderUnion::Status::Lit;
        return u;
    }
    if (!covered && u.occluders != lastCheck) {  // else merged and checked as they are
        shadows.merge();
        covered = checks && shadows.cover(*q.lit);
    }
    if (covered) {
        u.status = OccluderUnion::Status::Covered;
        return u;
    }
    u.shadows = shadows.paths();
    return u;
}

}  // namespace so
