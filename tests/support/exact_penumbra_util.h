// What the exact penumbra pass's tests share (exact_penumbra_test.cpp and
// hard_cases/exact_penumbra_cases_test.cpp): the closed-form scene's light as the pass sees it,
// occluder triangles with the tracer over them, and the pass at one point.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/scene.h"
#include "lambert.h"
#include "oracle/disk_bounds.h"
#include "oracle/polygon_visibility.h"
#include "test_scenes.h"

namespace so::test {

// The closed-form scene's light (test_scenes.h PenumbraScene): 2 x 1.5 at height 4, emitting down.
// A disk of radius 0.8 at height 4, emitting down (the disk tests' light).
inline DiskLightShape downDisk() {
    DiskLightShape d;
    d.center = {0.25, 4.0, 0.125};
    d.radius = 0.8;
    d.emitNormal = {0, -1, 0};
    diskAxes(d.emitNormal, d.e1, d.e2);
    return d;
}

inline const AxisRect kPenumbraLight = PenumbraScene{}.light;

// An AxisRect light as the exact pass takes it: cross(edgeU, edgeV) points down, as it emits.
inline RectLightShape lightShape(const AxisRect& l) {
    return {{l.x0, l.y, l.z0}, {l.x1 - l.x0, 0, 0}, {0, 0, l.z1 - l.z0}, {0, -1, 0}};
}

// A scene's rect light as the exact pass takes it, in world space.
inline RectLightShape rectLightShape(const Light& l) {
    return {l.wsPosition - 0.5 * l.wsU - 0.5 * l.wsV, l.wsU, l.wsV, l.wsEmitNormal()};
}

// Triangles as one mesh, with the tracer over them.
struct Occluders {
    std::vector<glm::dvec3> positions;
    std::vector<uint32_t> indices;
    void add(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
        const uint32_t base = uint32_t(positions.size());
        positions.insert(positions.end(), {a, b, c});
        indices.insert(indices.end(), {base, base + 1, base + 2});
    }
    void addRect(const AxisRect& r) {
        add({r.x0, r.y, r.z0}, {r.x1, r.y, r.z0}, {r.x1, r.y, r.z1});
        add({r.x0, r.y, r.z0}, {r.x1, r.y, r.z1}, {r.x0, r.y, r.z1});
    }
    ExactTracer tracer() const { return ExactTracer({{&positions, &indices}}); }
};

// V at p with no triangle left out and no cap that matters here.
inline PolygonVisibility visibility(const ExactTracer& t, const RectLightShape& light,
                                    const glm::dvec3& p, const glm::dvec3& n = {0, 1, 0}) {
    return rectLightVisibility(t, light, p, n, TriangleId{}, 1u << 20);
}

}  // namespace so::test
