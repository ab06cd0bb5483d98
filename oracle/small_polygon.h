// A convex polygon of a few vertices on the stack, and the clipping of a convex polygon by a
// half-space: what the exact penumbra pass clips for every candidate triangle of every pixel
// (polygon_visibility.h, occluder_union.h), so no allocation per clip. The same clipping serves
// the light regions of any size (a disk's n-gons, disk_bounds.h) as std::vector.
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
    // The std::vector spelling, for clipToHalfSpace.
    void push_back(const glm::dvec3& q) { push(q); }
    size_t size() const { return n; }
    const glm::dvec3& operator[](size_t i) const { return v[i]; }
    const glm::dvec3* begin() const { return v.data(); }
    const glm::dvec3* end() const { return v.data() + n; }
    glm::dvec3* begin() { return v.data(); }
    glm::dvec3* end() { return v.data() + n; }
};

// Sutherland-Hodgman: the part of the convex polygon where dot(normal, x) <= offset. Polygon:
// SmallPolygon or std::vector<glm::dvec3>.
template <typename Polygon>
Polygon clipToHalfSpace(const Polygon& poly, const ExactTracer::HalfSpace& h) {
    Polygon out{};
    const size_t count = poly.size();
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec3& a = poly[i];
        const glm::dvec3& b = poly[(i + 1) % count];
        const double da = glm::dot(h.normal, a) - h.offset, db = glm::dot(h.normal, b) - h.offset;
        if (da <= 0.0) out.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            out.push_back(a + t * (b - a));
        }
    }
    return out;
}

}  // namespace so
