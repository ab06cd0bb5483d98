// The exact shadow factor of a planar convex polygon light (a rect is its 4-gon) at a point
// (docs/oracle.md, "Exact penumbrae"): no sampling, no Embree, double precision throughout.
//
// V(p) = int_L v G dA / int_L G dA with G = max(cos_p, 0) max(cos_y, 0) / r^2 (area_light.h).
// Changing variables to the solid angle (dw = cos_y dA / r^2) makes each integral the
// cosine-weighted solid angle of a region of the light's plane seen from p, which Lambert's
// formula gives exactly from the region's boundary. So
//   V = Phi(L+ minus U) / Phi(L+),
// with L+ the light polygon clipped to p's upper half-space (where cos_p > 0) and U the union of
// the occluders' central projections through p onto the light's plane (occluder_union.h: each
// occluder triangle is clipped to the pyramid from p to L+ before it is projected, since parts
// behind p or beyond the light would project wrongly). The difference and the union are Clipper
// calls (Angus Johnson, Debian's libpolyclipping) on integer coordinates: robust on overlaps,
// shared edges and slivers. The light's (s, t) parameters are quantised to 2^-29 of its frame's
// edges, which moves V by about 1e-9.
//
// LightShadows splits the two steps, so that several light regions of one plane (a disk's
// inscribed and circumscribed polygons, disk_bounds.h) are integrated against one gathering of
// the occluders, or the visible part of the gathering polygon is handed to a region that is not a
// polygon (a disk's circle, disk_exact.h).
#pragma once

#include <cstdint>
#include <vector>

#include <polyclipping/clipper.hpp>

#include <glm/vec3.hpp>

#include "oracle/exact_tracer.h"
#include "oracle/occluder_union.h"

namespace so {

// A one-sided rectangle light: corner + s edgeU + t edgeV, s, t in [0, 1], emitting towards
// emitNormal (unit).
struct RectLightShape {
    glm::dvec3 corner{0.0}, edgeU{0.0}, edgeV{0.0}, emitNormal{0.0};
};

// A one-sided planar convex polygon light: `vertices` in order (either winding, at most
// kMaxVertices), emitting towards emitNormal (unit). The frame (corner, edgeU, edgeV) spans its
// plane: points are quantised to their (s, t) in corner + s edgeU + t edgeV, in units of 2^-29,
// so every vertex must have (s, t) in [0, 1] (Clipper's exact 64-bit range, and the covered
// shortcut's products: occluder_union.h).
struct PolygonLightShape {
    // A triangle clipped by the pyramid's sides (one per vertex of the light clipped to the
    // horizon) and the light's plane must fit SmallPolygon's fixed buffer.
    static constexpr size_t kMaxVertices = SmallPolygon::kCapacity - 5;
    glm::dvec3 corner{0.0}, edgeU{0.0}, edgeV{0.0}, emitNormal{0.0};
    std::vector<glm::dvec3> vertices;
};
// The rect as its 4-gon, its corners in the order corner, +edgeU, +edgeU+edgeV, +edgeV, its frame
// its own edges.
PolygonLightShape polygonOf(const RectLightShape& rect);

enum class PolygonVisibilityStatus : uint8_t {
    Exact,             // V is exact
    NoLight,           // no part of the light is above p's horizon on its emitting side: V = 0
    TooManyOccluders,  // more than the cap cut the pyramid: no answer (the caller samples)
    AlphaTested,       // an alpha-tested triangle cuts the pyramid: no answer (the caller samples)
};

// How an Exact answer was reached without a union (occluder_union.h): none of the pyramid's
// triangles cut it (V = 1), or their shadows were found to cover the light (V = 0).
enum class VisibilityShortcut : uint8_t { None, Lit, Covered };

struct PolygonVisibility {
    PolygonVisibilityStatus status = PolygonVisibilityStatus::NoLight;
    double V = 0.0;
    VisibilityShortcut shortcut = VisibilityShortcut::None;
    uint32_t occluders = 0;   // triangles whose clipped projection reached the union
    uint32_t candidates = 0;  // triangles the BVH query returned (the pyramid's cost)
    uint32_t backFaces = 0;   // of those, back faces left out (mesh_facing.h)
};

// V at p (unit normal n, the receiver's triangle `self` left out: it can only touch p's own
// plane) from every triangle of `tracer`. maxCandidates bounds the work per point. An
// alpha-tested triangle (ExactTracer::alphaTested) with a part inside the pyramid from p to the
// light ends the query with AlphaTested: its shadow is the mask's, which this does not clip.
// `more`: the union's shortcuts and back faces (occluder_union.h).
PolygonVisibility rectLightVisibility(const ExactTracer& tracer, const RectLightShape& light,
                                      const glm::dvec3& p, const glm::dvec3& n, TriangleId self,
                                      uint32_t maxCandidates, const OccluderOptions& more = {});
// The same for any convex polygon light (rectLightVisibility is this on polygonOf(light)).
PolygonVisibility polygonLightVisibility(const ExactTracer& tracer, const PolygonLightShape& light,
                                         const glm::dvec3& p, const glm::dvec3& n, TriangleId self,
                                         uint32_t maxCandidates, const OccluderOptions& more = {});

// The occluders' shadows on a light's plane seen from p, gathered once through the pyramid from p
// to `base` (a PolygonLightShape) clipped to p's horizon, and the integrals of any convex region
// of that plane inside `base` against them.
class LightShadows {
  public:
    LightShadows(const ExactTracer& tracer, const PolygonLightShape& base, const glm::dvec3& p,
                 const glm::dvec3& n, TriangleId self, uint32_t maxCandidates,
                 const OccluderOptions& more = {});
    // Exact: the integrals below hold; NoLight: base has no part above the horizon on its
    // emitting side (every region's integrals are 0); otherwise no answer.
    PolygonVisibilityStatus status() const { return result_.status; }
    // status, shortcut, occluders, candidates and back faces (V is not set: see integrals).
    const PolygonVisibility& counts() const { return result_; }

    // Phi((R+) minus U) and Phi(R+), both >= 0, for R+ the convex polygon `region` (in base's
    // plane, inside base, any number of vertices) clipped to p's horizon, U the occluders' shadows.
    struct Integrals {
        double visible = 0.0, whole = 0.0;
    };
    Integrals integrals(const std::vector<glm::dvec3>& region) const;
    // V of base itself, as rectLightVisibility gives it.
    double baseV() const;
    // The visible part of base above the horizon, for regions that are not polygons (a disk's,
    // disk_exact.h): base+ minus the shadows, as Clipper paths in frame()'s integers (outer
    // boundaries counter-clockwise, holes clockwise; none where the shadows cover it). Exact
    // status only.
    ClipperLib::Paths visiblePaths() const;
    const LightPlaneFrame& frame() const { return frame_; }

  private:
    LightPlaneFrame frame_;
    glm::dvec3 p_, n_;
    PolygonVisibility result_;
    ClipperLib::Path litPath_;  // base clipped to the horizon, quantised
    double litWhole_ = 0.0;
    ClipperLib::Paths shadows_;  // quantised, one per occluder (none after a shortcut)
    // Their union, made by the first call of integrals() and shared by the regions after it (a
    // cache: integrals() is const to its callers, and a LightShadows serves one thread).
    mutable ClipperLib::Paths union_;
    mutable bool united_ = false;
};

// Lambert's formula: the cosine-weighted solid angle int max(cos_p, 0) dw of the planar polygon
// `vertices` seen from p, for a polygon wholly on the upper side of p's horizon. Signed by the
// polygon's winding (the two windings give opposite signs), so that holes subtract.
double cosineWeightedSolidAngle(const glm::dvec3& p, const glm::dvec3& n,
                                const std::vector<glm::dvec3>& vertices);
// One edge's term of that sum: (1/2) int n . (r x dr) / |r|^2 along the segment from p + a to
// p + b (a, b relative to p), so that curved boundaries can be added to it (disk_exact.h).
double lambertEdge(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& n);

}  // namespace so
