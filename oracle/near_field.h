// The near field of a shadow ray's origin: the triangles the origin offset could hide.
//
// A shadow ray leaves from the surface point p moved kLsOriginOffset along the normal (offset.h),
// and moving the origin moves the whole segment towards the light: the true segment from p and
// the moved one bound a thin wedge, and a triangle whose edge or plane passes through that wedge
// is crossed by one and not the other. Near p that is no rare tangency: at a concave crease a
// neighbouring face rises from an edge a hair away, every direction that grazes it crosses it
// close to that edge, and the moved segment passes over (issue 42: on a real chess board 5% of a
// rect light's weight at one pixel, a 12-sigma error of the sampled pass). So every triangle
// within kNearFieldRadius of p is decided in double on the true segment from p
// (exact::rayTriangle), which no offset moves, wherever a segment can reach one; Embree then
// starts that segment beyond the ball (nearTnear), where the near field's triangles are the only
// ones, so it meets none of them there and needs no list of triangles to skip.
//
// What is left: a triangle farther than kNearFieldRadius from p can be missed only where it
// comes within the offset (2^-21 local units) of the true segment, a near-tangency of about
// 2^-10 radians or less seen from p, as float directions have anyway. docs/oracle.md states it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "oracle/accel.h"
#include "oracle/offset.h"

namespace so {

struct SurfaceBuffer;

// Local units (the frame scales the scene into [-1, 1]): 2^10 times the origin offset.
inline constexpr double kNearFieldRadius = 1024.0 * kLsOriginOffset;

struct NearTriangle {
    glm::dvec3 a, b, c;  // local frame, double
    glm::dvec3 n;        // unit normal
    glm::dvec3 p;        // the slot's surface point, where its true segments start
    double side = 0.0;   // n . (p - a): the slot's point above (or below) the plane
    // An alpha-tested triangle's mask and its vertices' texture coordinates: a crossing counts
    // where the mask keeps the point (core/alpha_mask.h, as the mesh's Embree filter tests it).
    const Accel::AlphaGeometry* alpha = nullptr;
    unsigned prim = 0;
};

// Every slot's near field in slot order (a compressed row list): slot s holds ids[begin[s] ..
// begin[s + 1]) (global triangle indices, Accel::originId) and the same range of triangles, so a
// tile's 16 slots hold one contiguous range. Not built (begin empty): no slot has one.
struct NearFields {
    std::vector<uint32_t> begin;
    std::vector<uint32_t> ids;
    std::vector<NearTriangle> triangles;
    // Per slot: where Embree starts its segments where the pass decides the slot's near field
    // (nearTnear), and the bound that rules the field out at once for most segments of a hard
    // light (nearSineBound; -inf where the field is empty).
    std::vector<float> tnear;
    std::vector<float> sineBound;
    std::vector<float> tileSineBound;  // per 4 x 4 tile: the largest of its slots' sineBound
    uint64_t pixels = 0;               // slots with a non-empty near field
    uint64_t pixelsShrunk = 0;  // slots whose ball shrank to hold at most 64 (the benches print it)
    uint64_t pixelsUnbounded = 0;  // slots whose sineBound is +inf: every hard-light lane decides
    uint64_t tilesUnbounded = 0;   // tiles with such a slot

    bool built() const { return !begin.empty(); }
    // Slots [first, last): the range of their near fields.
    uint32_t from(size_t first) const { return built() ? begin[first] : 0; }
    uint32_t to(size_t last) const { return built() ? begin[last] : 0; }
};

// The triangles within kNearFieldRadius of p (local frame, double), other than the origin
// triangle (mesh, prim) and other than triangles exactly in the origin's own plane (a segment
// leaving that plane on its lit side crosses them nowhere). Appended to ids and triangles.
// Where more than 64 triangles lie in the ball, the ball shrinks by 4 until they fit (at most 3
// times, so that it stays 16 offsets wide: nearTnear). Returns the ball's radius.
double appendNearField(const Accel& accel, const glm::dvec3& p, unsigned mesh, unsigned prim,
                       std::vector<uint32_t>& ids, std::vector<NearTriangle>& triangles);

// Where Embree may start a segment from a slot whose near field (a ball of `radius`) the pass
// decides in double: the ray's origin lies within 4 offsets of p and its direction is unit to a
// few ulp, so every point of the ray before this lies inside the ball, where only the near
// field's triangles are. The origin filter stays for the origin's own triangle.
float nearTnear(double radius);

// For a hard light, a slot's near field matters only to segments at a small angle to one of its
// triangles' planes. Let m0 be the slot's own unit normal on the side its rays leave (the camera's,
// as the pass's cosine m0 . dir has it), and turn T's normal n towards m0 (n . m0 >= 0), so that
// n . dir >= m0 . dir - |n - m0|. Where p and the ray's origin both lie above T's plane (along
// n), the origin beyond the float triangle's rounding, every segment with m0 . dir > |n - m0|
// leaves it: neither the true segment nor Embree's crosses T. Where p lies below, the true
// segment crosses the plane; at the sine s (|n . dir|) it meets it at X, |side| / s from p and at
// most that far from p's projection p', so X is at least inPlane - |side| / s from T (inPlane: p'
// to T); the moved segment differs from the true one only within kReach (1 + 1 / s) of X, so T
// matters only where s <= (|side| + kReach) / (inPlane - kReach), and every segment with
// m0 . dir above |n - m0| plus that is ruled out; where p lies on the plane to within 1e-12 (and
// the origin above), a segment at a sine over 1e-3 meets it within kNearContact, and every one
// with m0 . dir above |n - m0| + 1e-3 is ruled out. The bound returned is the largest over the
// triangles: a lane whose true m0 . dir exceeds it needs none of them, and Embree's answer
// stands. +inf where some triangle may matter at any direction; -inf for an empty field.
// origin: the slot's ray origin (SurfaceBuffer::lsRayOrigin).
float nearSineBound(const NearTriangle* triangles, size_t n, const glm::dvec3& m0,
                    const glm::dvec3& origin);

// sb.nearFields for every hit slot, in parallel; the same at any thread count.
void buildNearFields(const Accel& accel, SurfaceBuffer& sb);

// Where a slot's true segments start: its surface point in double (as fillSurfaceSlot rebuilt
// it). Every NearTriangle of the slot holds it too.
glm::dvec3 nearPoint(const Accel& accel, const SurfaceBuffer& sb, size_t s);

// An area light as the relevance test sees it: it lies in the convex hull of `points` (a rect's
// corners, a disk's or sphere's bounding box).
struct NearTarget {
    glm::dvec3 points[8];
    int count = 0;
};

// The triangles of [first, last) (one slot's) that a segment from the slot's point p to a point
// of the target can reach: where the whole target lies on p's side of T's plane, neither the true
// segment nor the moved one (from `origin`, the slot's ray origin) crosses T, if the origin lies
// on that side too beyond Embree's rounding; where the whole target lies across, every segment
// crosses the plane, at a sine that the target's corners bound from below, and above T's minSine
// (nearSineBound) too far from T to matter. Those are Embree's to decide; the rest are appended
// to ids and triangles (a pixel's list).
void appendRelevant(const NearFields& fields, uint32_t first, uint32_t last,
                    const NearTarget& target, const glm::dvec3& origin, std::vector<uint32_t>& ids,
                    std::vector<NearTriangle>& triangles);

// A segment meeting a triangle's plane within this many local units of p meets it where it
// touches the receiver at p itself (a pixel on an edge the two share, or contact): no occluder,
// as the exact test's t > 0 already says of a meeting at p, and 300 times under the offset the
// oracle's blind distance already admits (docs/oracle.md).
inline constexpr double kNearContact = 1e-9;

// The first crossing of p + t dir, t in (kNearContact, tMax) (see there), with the n triangles of
// one slot's list (p: their point), or +inf.
double nearFirstHit(const NearTriangle* triangles, size_t n, const glm::dvec3& dir, double tMax);

}  // namespace so
