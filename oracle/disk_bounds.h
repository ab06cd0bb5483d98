// Disk and sphere lights bounded by polygons (docs/oracle.md, "Disk and sphere lights"): V in a
// guaranteed interval, without sampling. This was the exact pass's method (issue 45); the pass now
// integrates the circle's arcs (disk_exact.h, issue 55) at about 1/50 of the cost, and this bound
// is its independent check (tests/oracle/disk_exact_test.cpp: the exact V lies in the interval).
// The geometry helpers below (the disk's frame, its closed form, the sphere's silhouette, the arc
// above the horizon, the polygons) serve both.
//
// The disk is not a polygon, but it lies between two: its inscribed n-gon P_in (vertices on the
// circle) and its circumscribed one P_out (edges tangent to it), P_in in disk in P_out. Both are
// clipped to p's horizon and integrated exactly against the occluders' shadows
// (polygon_visibility.h), and every integral below is of a non-negative integrand over a region
// that grows with the polygon, so with I the visible, U the unoccluded and O = U - I the occluded
// cosine-weighted solid angle:
//   I(P_in) <= I(disk) <= I(P_out),  U(P_in) <= U(disk) <= U(P_out),  O(P_in) <= O(disk) <=
//   O(P_out)
// and V = I / U = 1 - O / U lies in
//   [max(I_in / U_hi, 1 - O_out / U_lo), min(I_out / U_lo, 1 - O_in / U_hi)]
// with [U_lo, U_hi] = [U(P_in), U(P_out)], or U's closed form where the disk is wholly above the
// horizon. The width falls as 1/n^2 (the ring between the polygons has area ratio 1/cos^2(pi/n)).
// The polygons are doubled from minSides until the half-width reaches the target or maxSides.
//
// The polygons' vertices are quantised (polygon_visibility.h) by at most 2^-28.2 of the radius;
// P_in is built on a circle 2^-27 smaller and P_out around one 2^-27 larger, so the quantised
// polygons still enclose and are enclosed. The occluders' own quantisation (about 1e-9 of V, as
// for rect lights) is not in the polygons' bound (diskBoundAt): diskLightVisibility adds 1e-8 to
// both ends for it wherever a shadow reached the light.
//
// A sphere seen from p is the disk of its silhouette (sphereSilhouette): a uniformly emitting
// sphere gives p the irradiance of that disk, and each ray from p to the visible cap ends on it.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/trace_option_table.h"
#include "oracle/polygon_visibility.h"

namespace so {

// A one-sided disk light: centre + radius (cos t e1 + sin t e2), emitting towards emitNormal
// (unit; e1, e2 unit, orthogonal, in its plane).
struct DiskLightShape {
    glm::dvec3 center{0.0}, emitNormal{0.0}, e1{0.0}, e2{0.0};
    double radius = 0.0;
};
// Unit e1, e2 completing the unit normal m (the same construction as the sampled pass's).
void diskAxes(const glm::dvec3& m, glm::dvec3& e1, glm::dvec3& e2);

// The silhouette of a sphere (centre, radius R) seen from p at distance d > R: the circle where
// the cone from p touches it, of radius R sqrt(1 - R^2/d^2), in the plane at distance
// (d^2 - R^2)/d from p towards the centre, facing p.
DiskLightShape sphereSilhouette(const glm::dvec3& center, double radius, const glm::dvec3& p);

// Whether the whole disk lies strictly above p's horizon (unit normal n).
bool diskAboveHorizon(const DiskLightShape& disk, const glm::dvec3& p, const glm::dvec3& n);
// The cosine-weighted solid angle int cos_p dw of the disk seen from p, in closed form (the
// contour integral of Lambert's formula around the circle): for p on the emitting side and the
// disk wholly above p's horizon. A sphere's silhouette gives pi (R/d)^2 cos(theta).
double diskSolidAngle(const DiskLightShape& disk, const glm::dvec3& p, const glm::dvec3& n);

// The n-gons (n a power of two, 8 <= n <= kMaxSides): inscribed in the circle of radius
// radius * scale, and circumscribed about it (its edges tangent to it).
inline constexpr uint32_t kMaxDiskSides = kMaxBoundSides;  // the trace option table's limit
std::vector<glm::dvec3> inscribedPolygon(const DiskLightShape& disk, uint32_t sides, double scale);
std::vector<glm::dvec3> circumscribedPolygon(const DiskLightShape& disk, uint32_t sides,
                                             double scale);

// The arc of the disk's circle above p's horizon: angles (about e1 towards e2) within `half` of
// `center`; half = pi where all of it is above, 0 where none is.
struct DiskArc {
    double center = 0.0, half = 0.0;
};
DiskArc diskArcAbove(const DiskLightShape& disk, const glm::dvec3& p, const glm::dvec3& n);
// Polygons that put `sides` of their sides on the arc (equal steps, its ends included) and a few
// (steps of at most a quarter turn) round the rest of the circle: still inscribed in, and
// circumscribed about, the whole circle (any angles do, with gaps under half a turn), so the
// bound holds whatever the arc; it is tight where the horizon cuts the disk to a sliver. With
// half = pi, the regular polygons above.
std::vector<glm::dvec3> inscribedPolygon(const DiskLightShape& disk, uint32_t sides, double scale,
                                         const DiskArc& arc);
std::vector<glm::dvec3> circumscribedPolygon(const DiskLightShape& disk, uint32_t sides,
                                             double scale, const DiskArc& arc);

// The frame square both disk passes quantise a disk's plane in: half-side 1.25 radii about the
// centre, about their gathering octagons' vertices (at most 1.09 / cos(pi/8) = 1.18 radii).
inline constexpr double kDiskFrameHalfSide = 1.25;
// The light shape through which a disk's shadows are gathered: the `sides`-gon circumscribed
// about `scale` radii, in that frame.
PolygonLightShape diskGatheringShape(const DiskLightShape& disk, uint32_t sides, double scale);

struct DiskBoundOptions {
    double targetHalfWidth = 1e-6;  // `--bound-target`
    uint32_t minSides = 32;         // powers of two in [8, kMaxDiskSides]
    uint32_t maxSides = 4096;       // `--bound-max-sides`
};

// V in [lower, upper]; V = the midpoint.
struct DiskVisibility {
    PolygonVisibility counts;  // status, V, occluders, candidates
    double lower = 0.0, upper = 0.0;
    uint32_t sides = 0;         // of the last polygons integrated (0: none were needed)
    bool reachedTarget = true;  // false: maxSides stopped the doubling first
    double halfWidth() const { return 0.5 * (upper - lower); }
};

// The shadows of `tracer`'s triangles (the receiver's triangle `self` left out) on the disk seen
// from p (unit normal n); maxCandidates and `more` (the union's shortcuts and back faces) as for
// rectLightVisibility. Both hold for every region inside the gathering polygon
// (occluder_union.h), so for P_in and P_out: the covered shortcut gives [0, 0], exactly.
DiskVisibility diskLightVisibility(const ExactTracer& tracer, const DiskLightShape& disk,
                                   const glm::dvec3& p, const glm::dvec3& n, TriangleId self,
                                   uint32_t maxCandidates, const DiskBoundOptions& options,
                                   const OccluderOptions& more = {});

// The bound with `sides`-gons against shadows gathered by diskShadows (for tests: the width
// against n, and what the bound becomes with the polygons swapped).
LightShadows diskShadows(const ExactTracer& tracer, const DiskLightShape& disk, const glm::dvec3& p,
                         const glm::dvec3& n, TriangleId self, uint32_t maxCandidates,
                         const OccluderOptions& more = {});
struct DiskBound {
    double lower = 0.0, upper = 0.0;
};
DiskBound diskBoundAt(const LightShadows& shadows, const DiskLightShape& disk, const glm::dvec3& p,
                      const glm::dvec3& n, uint32_t sides);

}  // namespace so
