// A convex polygon of a few vertices on the stack, and its clipping by a half-space: what the
// exact penumbra pass clips for every candidate triangle of every pixel (polygon_visibility.h,
// occluder_union.h), so no allocation per clip.
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "core/error.h"
#include "oracle/exact_tracer.h"

namespace so {

// A triangle or the light's polygon, clipped by a few half-spaces (the pyramid's sides and the
// light's plane), each adding at most one vertex.
struct SmallPolygon {
    static constexpr size_t kCapacity = 16;
    std::array<glm::dvec3, kCapacity> v;
    size_t n = 0;
    SmallPolygon(std::initializer_list<glm::dvec3> points) {
        for (const glm::dvec3& q : points) push(q);
    }
    void push(const glm::dvec3& q) {
        SO_CHECK_LT(n, kCapacity);
        v[n++] = q;
    }
    const glm::dvec3* begin() const { return v.data(); }
    const glm::dvec3* end() const { return v.data() + n; }
    glm::dvec3* begin() { return v.data(); }
    glm::dvec3* end() { return v.data() + n; }
};

// Sutherland-Hodgman: the part of the convex polygon where dot(normal, x) <= offset.
inline SmallPolygon clipToHalfSpace(const SmallPolygon& poly, const ExactTracer::HalfSpace& h) {
    SmallPolygon out{};
    for (size_t i = 0; i < poly.n; ++i) {
        const glm::dvec3& a = poly.v[i];
        const glm::dvec3& b = poly.v[(i + 1) % poly.n];
        const double da = glm::dot(h.normal, a) - h.offset, db = glm::dot(h.normal, b) - h.offset;
        if (da <= 0.0) out.push(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            out.push(a + t * (b - a));
        }
    }
    return out;
}

}  // namespace so
