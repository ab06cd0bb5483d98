// The exact shadow factor of a rectangular light at a point (docs/oracle.md, "Exact penumbrae"):
// no sampling, no Embree, double precision throughout.
//
// V(p) = int_L v G dA / int_L G dA with G = max(cos_p, 0) max(cos_y, 0) / r^2 (area_light.h).
// Changing variables to the solid angle (dw = cos_y dA / r^2) makes each integral the
// cosine-weighted solid angle of a region of the light's plane seen from p, which Lambert's
// formula gives exactly from the region's boundary. So
//   V = Phi(L+ minus U) / Phi(L+),
// with L+ the light polygon clipped to p's upper half-space (where cos_p > 0) and U the union of
// the occluders' central projections through p onto the light's plane. Each occluder triangle is
// clipped to the pyramid from p to L+ before it is projected (parts behind p or beyond the light
// would project wrongly). The difference and the union are one call of Clipper (Angus Johnson,
// Debian's libpolyclipping) on integer coordinates: robust on overlaps, shared edges and slivers.
// The light's (s, t) parameters are quantised to 2^-29 of its edges, which moves V by about 1e-9.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "oracle/exact_tracer.h"
#include "oracle/occluder_union.h"

namespace so {

// A one-sided rectangle light: corner + s edgeU + t edgeV, s, t in [0, 1], emitting towards
// emitNormal (unit).
struct RectLightShape {
    glm::dvec3 corner{0.0}, edgeU{0.0}, edgeV{0.0}, emitNormal{0.0};
};

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

// Lambert's formula: the cosine-weighted solid angle int max(cos_p, 0) dw of the planar polygon
// `vertices` seen from p, for a polygon wholly on the upper side of p's horizon. Signed by the
// polygon's winding (the two windings give opposite signs), so that holes subtract.
double cosineWeightedSolidAngle(const glm::dvec3& p, const glm::dvec3& n,
                                const std::vector<glm::dvec3>& vertices);

}  // namespace so
