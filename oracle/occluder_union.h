// The occluders' side of the exact penumbra pass (docs/oracle.md, "Exact penumbrae"): which part
// of a polygonal light a point sees, as integer polygons in the light's plane. The triangles that
// may cut the pyramid from the point to the light come from the exact tracer's BVH; each is clipped
// to the pyramid, projected centrally through the point onto the light's plane and quantised; the
// visible part of a region is the region minus the union of those shadows (lightMinusShadows, one
// Clipper call: integer arithmetic, so overlaps, shared edges and slivers cannot make it fail).
// The gathering is done once per point for the pyramid of a base polygon, and any region inside the
// base is integrated against it (polygon_visibility.h's LightShadows: a rect, or a disk's
// inscribed and circumscribed n-gons).
//
// Whole triangles go to the union as their patch's outline, not one by one: their shared edges
// cancel (mergeEdges in the .cpp; the same filled region). A triangle is whole where the pyramid
// does not cut it, and also where it lies between p's level and the light's plane (the slab) with
// its projection near the light: the projection of the whole triangle, unclipped, covers the
// same part of the light as the projection of its part inside the pyramid, so the triangles of a
// closed mesh's front faces leave only their silhouette loops (issue 45, "project only silhouette
// loops").
//
// With `facing` (mesh_facing.h), the back faces of closed meshes are left out: the union is the
// same region (to the quantisation: a shared edge clipped from its two triangles may round to
// neighbouring integers). The rule is about segments from the point (mesh_facing.h): a segment to
// any point of the light's plane that a closed part blocks is blocked by a kept triangle, at a
// crossing on the segment, so inside the pyramid; it holds for every region inside the base.
//
// Shortcuts that give the same answer as the plain union:
// - no triangle cuts the pyramid: the whole light is visible, without a union;
// - the light is covered: as soon as one shadow holds the whole light, or the shadows so far
//   (checked when their count reaches 64, 512, 4,096, ..., and once at the end) are found to cover
//   it, the query stops (or the union is skipped): more triangles can only cover more. The check
//   needs no Clipper: each connected patch of whole triangles (and each clipped polygon) has a
//   winding number >= 0 everywhere, constant over the light's interior where none of its edges
//   crosses it; if those constants add up to 1 or more, the plain union (non-zero filling) holds
//   the light. "The light" is the base above the horizon, so every region inside it is covered
//   as well.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <polyclipping/clipper.hpp>

#include "oracle/exact_tracer.h"
#include "oracle/mesh_facing.h"
#include "oracle/small_polygon.h"

namespace so {

// The light's plane with integer coordinates: y = origin + s edgeU + t edgeV, (s, t) quantised to
// 2^-29 (below Clipper's 2^30 "low range", where its arithmetic is plain 64-bit and exact). The
// light's own (s, t) lie in [0, 1], so its polygons have coordinates in [0, 2^29] (a disk's frame
// is a square about its gathering polygon: disk_bounds.h); the slab's unclipped triangles are
// kept within half the square of it, [-2^28, 3 2^28], still in the low range.
struct LightPlaneFrame {
    static constexpr double kQuantum = double(1 << 29);
    glm::dvec3 origin{0.0}, edgeU{0.0}, edgeV{0.0}, emitNormal{0.0};
    double invUU = 0.0, invVV = 0.0;
    LightPlaneFrame(const glm::dvec3& origin, const glm::dvec3& edgeU, const glm::dvec3& edgeV,
                    const glm::dvec3& emitNormal);
    ClipperLib::IntPoint quantised(const glm::dvec3& y) const;
    glm::dvec3 point(const ClipperLib::IntPoint& q) const;
    // The polygon (in the plane) quantised, wound counter-clockwise like every path here.
    ClipperLib::Path path(const SmallPolygon& poly) const;
    ClipperLib::Path path(const std::vector<glm::dvec3>& poly) const;
};

// What a caller chooses of the union's work.
struct OccluderOptions {
    bool shortcuts = true;               // the lit and covered shortcuts (tests turn them off)
    bool merge = true;                   // whole triangles' shared edges merged (above)
    const MeshFacing* facing = nullptr;  // back faces left out (mesh_facing.h), or null
};

// One point's question.
struct OccluderQuery {
    glm::dvec3 p{0.0};  // the receiving point
    TriangleId self;    // its triangle, left out: it can only touch p's own plane
    // dot(emitNormal, p - origin) > 0: p's height above the light's plane.
    double height = 0.0;
    // The pyramid from p to the visible light: its sides through p, then the light's plane (p's
    // side of it), last (the slab's test reads it there).
    const std::vector<ExactTracer::HalfSpace>* pyramid = nullptr;
    const LightPlaneFrame* frame = nullptr;
    const ClipperLib::Path* lit = nullptr;  // the base above the horizon, quantised (frame.path)
    uint32_t maxCandidates = 0;             // candidates beyond this: TooManyOccluders
    OccluderOptions options;
};

struct OccluderUnion {
    enum class Status : uint8_t {
        Partial,           // `shadows` holds the shadows (possibly none)
        Lit,               // no triangle cut the pyramid: the whole light is visible, no union
        Covered,           // the shadows cover the light: nothing visible (found early)
        TooManyOccluders,  // more candidates than maxCandidates: no answer
        AlphaTested,       // an alpha-tested triangle cuts the pyramid: no answer
    };
    Status status = Status::Partial;
    // Partial: the shadows met, as paths whose non-zero filling is their union (a merged patch's
    // outline, or one counter-clockwise path per shadow).
    ClipperLib::Paths shadows;
    uint32_t occluders = 0;    // shadows that reached the union (up to where it stopped)
    uint32_t candidates = 0;   // triangles the BVH query returned (the pyramid's cost)
    uint32_t backFaces = 0;    // candidates left out by `facing`
    uint32_t coverChecks = 0;  // covered checks made before the last (each merges the shadows)
};

OccluderUnion gatherShadows(const ExactTracer& tracer, const OccluderQuery& q);

// `light` minus the union of `shadows` (non-zero filling: every path counter-clockwise).
ClipperLib::Paths lightMinusShadows(const ClipperLib::Path& light,
                                    const ClipperLib::Paths& shadows);

}  // namespace so
