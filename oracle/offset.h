// Shadow-ray origins (docs/oracle.md, "How it stays exact").
//
// The oracle's policy (OffsetPolicy::ErrorBound): the hit point is rebuilt in double on the
// double-precision triangle, so its error is that of rounding to float (2^-25 in the local frame,
// where every coordinate is below 1), not the error of org + t * dir. The origin moves only
// kLsOriginOffset along the normal, a small multiple of that bound, and the filter on every
// geometry (accel.h) skips the triangle the ray leaves from. Moving the origin moves the whole
// ray: an occluder that the ray clips by less than the offset anywhere along it is missed, so the
// offset must be as small as the arithmetic allows (issue 9: the earlier 256-ulp offset missed a
// crease of the Stanford bunny 0.09 units from the receiver).
//
// OffsetPolicy::Legacy256Ulp keeps the earlier rule for the tests that show the verifier catches
// what it missed: the integer-ulp offset of Waechter and Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6), made for points computed as org + t dir.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

namespace so {

enum class OffsetPolicy { ErrorBound, Legacy256Ulp };

// The error-bound policy's offset along the normal, in local units (|coordinates| < 1 there):
// 8 * 2^-24 = 2^-21, four float spacings at 1 and 16 times the rounding error of a hit point, and
// half the tolerance the verifier holds the oracle to (verify.h). Measured (docs/oracle.md): with
// no offset at all the grazing-plane test gets false self-shadows from coplanar neighbours; from
// 1 * 2^-24 on it gets none; 8 is that times eight. 32 * 2^-24 already misses bunny creases.
inline constexpr double kLsOriginOffset = 8.0 / 16777216.0;

// The origin for a ray leaving the surface point p (double, local frame) on the side of the unit
// normal n.
inline glm::vec3 errorBoundOrigin(const glm::dvec3& p, const glm::dvec3& n) {
    return glm::vec3(p + kLsOriginOffset * n);
}

// The cosine, between a shadow ray leaving from errorBoundOrigin on triangle (a, b, c) (double,
// local frame) and the triangle's normal, from which on Embree's float arithmetic cannot report
// the triangle itself as hit: such a ray needs no origin filter (accel.h). +inf where even the
// side of the triangle the origin lies on is within Embree's rounding (large triangles out of the
// axis planes, thin ones): rays from there always run the filter. The bound follows Embree's robust
// test operation by operation, with every rounding bounded from the triangle's extent per axis
// (offset.cpp; docs/oracle.md, "The origin filter, where it can matter"), times two.
// tests/oracle/hard_cases/origin_tangency_test.cpp traces rays at the bound without the filter on
// generated triangles and finds no self-hit.
float originTangencyBound(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

namespace offset_detail {
inline constexpr float kOrigin = 1.0f / 32.0f;  // below this, ulps are too small: go linear
inline constexpr float kFloatScale = 1.0f / 65536.0f;
inline constexpr float kIntScale = 256.0f;

inline float offsetComponent(float p, float n) {
    int32_t ofi = int32_t(kIntScale * n);
    float pi = std::bit_cast<float>(std::bit_cast<int32_t>(p) + (p < 0.0f ? -ofi : ofi));
    return std::fabs(p) < kOrigin ? p + kFloatScale * n : pi;
}
}  // namespace offset_detail

// Legacy256Ulp. p: point on the surface, n: unit geometric normal on the side the ray leaves from.
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n) {
    return {offset_detail::offsetComponent(p.x, n.x), offset_detail::offsetComponent(p.y, n.y),
            offset_detail::offsetComponent(p.z, n.z)};
}

// The margin the same rule leaves around a point that is not on a surface (the far end of a
// shadow ray at a light): an upper bound of offsetRayOrigin's displacement at p.
inline float offsetMargin(const glm::vec3& p) {
    float m = 0.0f;
    for (int i = 0; i < 3; ++i) {
        float a = std::fabs(p[i]);
        float step = a < offset_detail::kOrigin
                         ? offset_detail::kFloatScale
                         : std::nextafter(a, INFINITY) - a;  // one ulp at |p_i|
        m = std::max(m, a < offset_detail::kOrigin ? step : offset_detail::kIntScale * step);
    }
    return m * 1.7320508f;  // all three components at once
}

}  // namespace so
