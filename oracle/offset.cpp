#include "oracle/offset.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace so {

namespace {

constexpr double kU = 1.0 / 16777216.0;  // 2^-24, float's unit roundoff

// Upper bounds of the error Embree's float arithmetic adds to a vector, per component.
using Bound3 = glm::dvec3;

// The error of a cross-product component a1 b2 - a2 b1 computed in float from inputs with errors
// da, db and magnitudes at most ma, mb: the inputs' errors carried through, and two roundings
// (with or without a fused multiply-subtract).
double crossComponentError(double ma1, double mb2, double ma2, double mb1, double da1, double db2,
                           double da2, double db1) {
    const double carried = da1 * (mb2 + db2) + ma1 * db2 + da2 * (mb1 + db1) + ma2 * db1;
    return carried + 2.0 * kU * ((ma1 + da1) * (mb2 + db2) + (ma2 + da2) * (mb1 + db1));
}

}  // namespace

// Embree's robust (Pluecker) test, for a ray from O along D against triangle V0 V1 V2, all float:
// v_i = V_i - O, edges e0 = v2 - v0, e1 = v0 - v1, e2 = v1 - v2, Ng = cross(e0, e1) or cross(e1,
// e2) per component (stable_triangle_normal), den = 2 dot(Ng, D), T = 2 dot(v0, Ng); a hit needs
// T and den of one sign (whatever the edge tests say). For a ray leaving the origin's side of the
// triangle, den and T have opposite signs in exact arithmetic; the bound keeps both signs right
// despite the rounding. The error bounds hold for any origin on the triangle: they use the
// triangle's extent per axis (|v_i| <= extent + the offset), so a triangle in an axis plane, whose
// normal Embree computes almost exactly, gets a small bound.
float originTangencyBound(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    constexpr float kAlways = std::numeric_limits<float>::infinity();
    // The triangle as Embree holds it, and its exact normal there.
    const glm::dvec3 fa = glm::dvec3(glm::vec3(a)), fb = glm::dvec3(glm::vec3(b)),
                     fc = glm::dvec3(glm::vec3(c));
    const glm::dvec3 ng = glm::cross(fb - fa, fc - fa);
    const double ngLength = glm::length(ng);
    const glm::dvec3 nd = glm::cross(b - a, c - a);
    if (!(ngLength > 0.0) || !(glm::length(nd) > 0.0)) return kAlways;
    const glm::dvec3 lo = glm::min(fa, glm::min(fb, fc)), hi = glm::max(fa, glm::max(fb, fc));
    const Bound3 extent = hi - lo;
    // |v_i| per axis: the extent, plus the origin's offset (8u) and rounding (u) off the surface.
    const Bound3 mv = extent + 9.0 * kU;
    const Bound3 dv = kU * mv;                              // v_i = fl(V_i - O)
    const Bound3 de = 2.0 * dv * (1.0 + kU) + kU * extent;  // e = fl(v_a - v_b), |e| <= extent
    const Bound3 me = extent + de;
    // Every pair of edges has the same bounds, so one formula covers cross(e0, e1) and cross(e1,
    // e2) alike.
    const Bound3 dn(crossComponentError(me.y, me.z, me.z, me.y, de.y, de.z, de.z, de.y),
                    crossComponentError(me.z, me.x, me.x, me.z, de.z, de.x, de.x, de.z),
                    crossComponentError(me.x, me.y, me.y, me.x, de.x, de.y, de.y, de.x));
    const Bound3 mn = glm::abs(ng) + dn;
    // T = dot(v0, Ng): the inputs' errors carried through, and three roundings.
    double errorT = 0.0;
    for (int k = 0; k < 3; ++k)
        errorT += dv[k] * mn[k] + mv[k] * dn[k] + 3.0 * kU * (mv[k] + dv[k]) * mn[k];
    // The origin lies 8u above the double triangle along its normal, rounded to float (at most
    // sqrt(3) u / 2 off); the float triangle passes at most as far from each point of the double
    // one, and its normal turns by the angle between them.
    const glm::dvec3 ndUnit = nd / glm::length(nd);
    const glm::dvec3 ngUnit = ng / ngLength * (glm::dot(ng, nd) < 0.0 ? -1.0 : 1.0);
    const double height = 8.0 * kU * glm::dot(ngUnit, ndUnit) - std::sqrt(3.0) * kU;
    if (!(height > 0.0 && 2.0 * errorT <= height * ngLength)) return kAlways;
    // den = dot(Ng, D) with |D| = 1: Ng's error, and three roundings.
    const double errorDen = glm::length(dn) + 3.0 * kU * (ngLength + glm::length(dn));
    // The ray's cosine as the oracle computes it: to the float normal of the double triangle
    // (rounded by sqrt(3) u / 2), in float arithmetic (4u); the float triangle's normal differs
    // from the double one's by the angle between them.
    const double cosineError =
        4.0 * kU + std::sqrt(3.0) * kU + glm::length(ngUnit - ndUnit) + errorDen / ngLength;
    const double bound = 2.0 * cosineError;  // a margin of two over the sum of the bounds
    const float f = float(bound);
    return double(f) >= bound ? f : std::nextafter(f, kAlways);
}

}  // namespace so
