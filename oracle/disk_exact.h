// Disk and sphere lights in the exact pass (docs/oracle.md, "Disk and sphere lights"): V by
// clipping the occluders' shadows against the circle and integrating along its arcs.
//
// V = Phi(D+ minus U) / Phi(D+), with D+ the disk clipped to p's horizon, U the union of the
// occluders' shadows on its plane and Phi the cosine-weighted solid angle seen from p. Lambert's
// formula is a contour integral, Phi(R) = (1/2) oint_dR n . (r x dr) / |r|^2 (r = x - p), so it
// needs no polygon: the boundary of D cap P, for P a polygon with holes, is the part of P's edges
// inside the disk (P's orientation) and the arcs of the circle inside P (counter-clockwise).
// Along the edges the integral is Lambert's closed form (lambertEdge); along an arc the
// integrand is analytic in the angle, (a + b cos t + c sin t) / (A + B cos t + C sin t) with
// A > sqrt(B^2 + C^2) for p off the disk's plane, so Gauss-Legendre converges geometrically:
// each arc is integrated with 16 and 32 nodes, split in halves where they differ by more than
// 1e-14 of the scale, and the difference is stated as the arc's error (it overstates the
// 32-node rule's error by orders of magnitude on an analytic integrand).
//
// The shadows are gathered once (polygon_visibility.h's LightShadows) through the pyramid of the
// disk's circumscribed octagon (SmallPolygon holds no more sides), and Clipper gives the visible
// part of the octagon above the horizon, P = octagon+ minus U, in integers. The octagon's edges
// keep 2^-20 of the radius outside the circle (the quantisation moves them by 2^-28), so only
// the horizon's and the shadows' edges cross it. Phi(D+) is the closed form (diskSolidAngle)
// where the disk is wholly above the horizon, otherwise the contour of the arc above it and its
// chord, with no quantisation.
//
// The stated error of V: the arcs' errors and a rounding allowance (16 ulps of the sum of the
// contour's terms' magnitudes) of both integrals, propagated through the ratio, plus 1e-8
// wherever a shadow reached the light, for the shadows' quantisation, as for the bound it
// replaces (disk_bounds.h, now the independent check: tests and docs/oracle.md).
//
// A sphere seen from p is the disk of its silhouette (disk_bounds.h's sphereSilhouette).
// Nothing is shared between points: the same answer at any thread count.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "oracle/disk_bounds.h"
#include "oracle/polygon_visibility.h"

namespace so {

// A cosine-weighted solid angle and the error stated for it.
struct DiskIntegral {
    double value = 0.0, error = 0.0;
};

// Phi(D+) for p on the disk's emitting side: 0 where no part is above the horizon.
DiskIntegral diskUnoccludedSolidAngle(const DiskLightShape& disk, const glm::dvec3& p,
                                      const glm::dvec3& n);

// Phi(D cap P) for P the union of `region`'s closed paths in the disk's plane, as (u, v) in
// centre + u e1 + v e2; outer boundaries counter-clockwise, holes clockwise, not overlapping
// (Clipper's output). P's part below p's horizon must be left out by the caller (it counts
// negative there).
DiskIntegral diskRegionSolidAngle(const DiskLightShape& disk, const glm::dvec3& p,
                                  const glm::dvec3& n,
                                  const std::vector<std::vector<glm::dvec2>>& region);

// V at p with its stated error: counts as rectLightVisibility gives them (status, occluders,
// candidates, back faces, shortcut) and V = counts.V.
struct DiskExactVisibility {
    PolygonVisibility counts;
    double error = 0.0;  // |V - the true V| <= error
    // The gathering polygon's sides where the shadows were clipped against it and the contour
    // integrated (kDiskGatheringSides), 0 where a shortcut answered: the work oracle.json's
    // bound.sides_total and --penumbra auto's probe count (penumbra_choice.h).
    uint32_t sides = 0;
};
inline constexpr uint32_t kDiskGatheringSides = 8;

// The shadows of `tracer`'s triangles (the receiver's triangle `self` left out) on the disk
// seen from p (unit normal n); maxCandidates and `more` as for rectLightVisibility.
DiskExactVisibility diskLightExact(const ExactTracer& tracer, const DiskLightShape& disk,
                                   const glm::dvec3& p, const glm::dvec3& n, TriangleId self,
                                   uint32_t maxCandidates, const OccluderOptions& more = {});

}  // namespace so
