// Closed-form references for area-light tests: Lambert's polygon formula and the exact shadow
// factor of a rectangle light behind a parallel rectangle occluder. Written in double and
// independently of the oracle, so tests can hold the oracle (and sampled estimates) to it.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace so::test {

// The integral over a planar convex polygon of
//   G(p, y) = max(0, cos_p) max(0, cos_y) / r^2 dA(y),
// cos_p = n . unit(y - p), cos_y = emitNormal . unit(p - y): the unoccluded irradiance at p from
// a unit-radiance Lambertian emitter, times pi (the course notes' form factor is this / pi).
// The emitter is one-sided: 0 when p is behind it or in its plane. Parts of the polygon below p's
// horizon are clipped away first, so the result stays exact for tilted receivers. Either winding
// gives the same answer; n and emitNormal need not be unit length. Degenerate input gives 0.
double polygonIrradiance(const glm::dvec3& p, const glm::dvec3& n,
                         const std::vector<glm::dvec3>& poly, const glm::dvec3& emitNormal);

// The rectangle {x0 <= x <= x1, z0 <= z <= z1} in the horizontal plane at height y.
struct AxisRect {
    double y;
    double x0, x1, z0, z1;
};

// Its four corners, counter-clockwise seen from above.
std::vector<glm::dvec3> axisRectPolygon(const AxisRect& r);

// The irradiance-weighted visibility V(p) = int_L v G dA / int_L G dA of a light rectangle that
// emits downwards, with a parallel occluder rectangle below it (light.y > occluder.y); v = 1 when
// the open segment p -> y misses the occluder. n is the receiver normal at p (any direction).
// Exact: from p below the occluder, the occluder's shadow on the light plane is an axis-aligned
// rectangle, so the visible light is at most four rectangles, each integrated by Lambert.
// V = 0 exactly in the umbra and 1 exactly where the occluder cannot block (p at or above its
// plane, or its projection misses the light). Where no part of the light is above p's horizon or
// p is not below the light, the denominator is 0 and this returns 0, as the oracle reports.
double exactRectLightRectOccluderV(const glm::dvec3& p, const glm::dvec3& n, const AxisRect& light,
                                   const AxisRect& occluder);

// The visible fraction of the light's area (no cosines, no 1/r^2, no horizon): what an unweighted
// estimate such as PCF-style area averaging converges to. Same conventions at the ends: 1 where
// the occluder cannot block, 0 in the umbra and where the weighted denominator is 0.
double exactRectLightUnweightedFraction(const glm::dvec3& p, const glm::dvec3& n,
                                        const AxisRect& light, const AxisRect& occluder);

}  // namespace so::test
