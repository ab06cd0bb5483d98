// Exact signs for the oracle's in-or-out decisions where float arithmetic cannot tell them apart
// (docs/oracle.md, "Exact facing"): is the light above the plane of the triangle a pixel sees, is
// that triangle in front of a one-sided emitter. The scene's world-space doubles are the geometry
// the oracle answers for, and each decision is the sign of a polynomial in them. A double-precision
// filter with a proven error bound (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
// Fast Robust Geometric Predicates", 1997) decides almost every call; the rest are evaluated
// exactly with dyadic integers (GMP): every double is m 2^e, and so are sums and products of them.
//
// Signs are -1, 0 or +1, and exact: 0 means exactly zero in real arithmetic on the given doubles.
#pragma once

#include <glm/vec3.hpp>

namespace so::exact {

// sign(((b - a) x (c - a)) . (q - a)): +1 where q lies on the side of the triangle (a, b, c) that
// its counter-clockwise normal points to, 0 in its plane. q is q0 + q1 + q2, summed exactly (a
// rect light's corner: centre +- u/2 +- v/2).
int orient(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& q0,
           const glm::dvec3& q1 = glm::dvec3(0.0), const glm::dvec3& q2 = glm::dvec3(0.0));

// sign(((b - a) x (c - a)) . d): whether the direction d points to the normal's side.
int orientDirection(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                    const glm::dvec3& d);

// sign((u x v) . (q - o)): the side of q with respect to the plane through o spanned by u and v
// (a rect light's plane; it emits on the side of u x v).
int sideOfSpan(const glm::dvec3& o, const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& q);

// sign(m . (q - o)): the side of q with respect to the plane through o with normal m.
int sideOfPlane(const glm::dvec3& o, const glm::dvec3& m, const glm::dvec3& q);

// Whether some point of the disk (centre o, normal m of any length, radius r >= 0) lies strictly
// on the normal's side of the plane of the triangle (a, b, c), as orient() orients it.
bool diskAbovePlane(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                    const glm::dvec3& o, const glm::dvec3& m, double r);

// How many calls the double filter could not decide (exact arithmetic ran), over the process; for
// tests and benchmarks.
unsigned long long exactEvaluations();

}  // namespace so::exact
