#include "oracle/occluder_union.h"

#include <cmath>

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
// so dot(emitNormal, q - p) is in [-height, 0)), quantised. Empty where nothing is left.
Path shadowOf(const dvec3& a, const dvec3& b, const dvec3& c, const OccluderQuery& q) {
    SmallPolygon part{a, b, c};
    for (const ExactTracer::HalfSpace& h : *q.pyramid) {
        part = clipToHalfSpace(part, h);
        if (part.n < 3) return {};
    }
    for (dvec3& y : part) {
        const double along = glm::dot(q.frame->emitNormal, y - q.p);
        if (!(along < 0.0)) return {};  // at p itself: only a triangle through p
        y = q.p + (y - q.p) * (-q.height / along);
    }
    return q.frame->path(part);
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
bool holds(const Path& shadow, const Path& lit) {
    Path v;
    for (const IntPoint& q : shadow)
        if (v.empty() || !(q == v.back())) v.push_back(q);
    while (v.size() > 1 && v.front() == v.back()) v.pop_back();
    const size_t n = v.size();
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

template <typename Polygon>
Path quantisedPath(const LightPlaneFrame& frame, const Polygon& poly) {
    Path out;
    out.reserve(poly.size());
    for (const dvec3& y : poly) out.push_back(frame.quantised(y));
    if (!ClipperLib::Orientation(out)) ClipperLib::ReversePath(out);  // all windings alike
    return out;
}

}  // namespace

Paths lightMinusShadows(const Path& light, const Paths& shadows) {
    ClipperLib::Clipper clipper;
    clipper.AddPath(light, ClipperLib::ptSubject, true);
    clipper.AddPaths(shadows, ClipperLib::ptClip, true);
    Paths visible;
    clipper.Execute(ClipperLib::ctDifference, visible, ClipperLib::pftNonZero,
                    ClipperLib::pftNonZero);
    return visible;
}

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

OccluderUnion gatherShadows(const ExactTracer& tracer, const OccluderQuery& q) {
    OccluderUnion u;
    Paths shadows;
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
        Path shadow = shadowOf(a, b, c, q);
        if (shadow.empty()) return true;
        if (tracer.alphaTested(id)) {
            alpha = true;
            return false;
        }
        ++u.occluders;
        if (q.options.shortcuts && holds(shadow, *q.lit)) covered = true;
        shadows.push_back(std::move(shadow));
        if (q.options.shortcuts && !covered && u.occluders == nextCheck) {
            nextCheck *= 4;
            ++u.unions;
            covered = lightMinusShadows(*q.lit, shadows).empty();
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
    u.shadows = std::move(shadows);
    return u;
}

}  // namespace so
