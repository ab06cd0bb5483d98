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
// (exact::rayTriangle), which no offset moves, and skipped by Embree (the filter, accel.h).
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
    uint64_t pixels = 0;        // slots with a non-empty near field
    uint64_t pixelsShrunk = 0;  // slots whose ball shrank to hold at most 64 (the benches print it)

    bool built() const { return !begin.empty(); }
    // Slots [first, last): the range of their near fields.
    uint32_t from(size_t first) const { return built() ? begin[first] : 0; }
    uint32_t to(size_t last) const { return built() ? begin[last] : 0; }
};

// The triangles within kNearFieldRadius of p (local frame, double), other than the origin
// triangle (mesh, prim) and other than triangles exactly in the origin's own plane (a segment
// leaving that plane on its lit side crosses them nowhere). Appended to ids and triangles.
// Where more than 64 triangles lie in the ball, the ball shrinks by 4 until they fit (at most 8
// times): returns whether it shrank.
bool appendNearField(const Accel& accel, const glm::dvec3& p, unsigned mesh, unsigned prim,
                     std::vector<uint32_t>& ids, std::vector<NearTriangle>& triangles);

// sb.nearFields for every hit slot, in parallel; the same at any thread count.
void buildNearFields(const Accel& accel, SurfaceBuffer& sb);

// Where a slot's true segments start: its surface point in double (as fillSurfaceSlot rebuilt
// it), its triangle's normal (not unit) and global index.
struct NearOrigin {
    glm::dvec3 p, normal;
    uint32_t id;
};
NearOrigin nearOrigin(const Accel& accel, const SurfaceBuffer& sb, size_t s);

// The light as the relevance test sees it: it lies in the convex hull of `points` (a point light's
// position, a rect's corners, a disk's or sphere's bounding box), or, directional, infinitely far
// along `direction` (towards the light).
struct NearTarget {
    glm::dvec3 points[8];
    int count = 0;
    bool atInfinity = false;
    glm::dvec3 direction{0.0};
};

// The triangles of [first, last) that a segment from origin.p to the target can come within
// reach of: a triangle whose plane lies more than the offset from p, with the whole target on
// p's side of it, is crossed by neither the true segment nor the moved one, and Embree's answer
// for it stands. Appended to ids and triangles (a packet's list).
void appendRelevant(const NearFields& fields, uint32_t first, uint32_t last,
                    const NearOrigin& origin, const NearTarget& target, std::vector<uint32_t>& ids,
                    std::vector<NearTriangle>& triangles);

// Whose near field a list holds: the origin's own (appendNearField left out its triangle and
// those in its plane already), or a tile's, which may hold them for another lane.
enum class NearList { Own, Tile };

// The first crossing of origin.p + t dir, t in (0, tMax), with the n triangles, or +inf. From a
// tile's list, the origin's own triangle and triangles exactly in its plane are skipped.
double nearFirstHit(const uint32_t* ids, const NearTriangle* triangles, size_t n, NearList list,
                    const NearOrigin& origin, const glm::dvec3& dir, double tMax);

}  // namespace so
