// Self-intersection-safe ray origins: the integer-ulp offset of Waechter and Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6). A fixed epsilon is too
// large near the origin (contact shadows leak) and too small far from it (acne); moving the origin
// a fixed number of ulps along the normal scales with the float spacing at the point instead.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

namespace so {

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

// p: point on the surface, n: unit geometric normal on the side the ray leaves from.
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
