#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "core/error.h"

namespace so {

void Bounds3d::extend(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

void Bounds3d::extend(const Bounds3d& b) {
    if (b.empty()) return;
    extend(b.lo);
    extend(b.hi);
}

double Bounds3d::extent() const {
    return empty() ? 0.0 : glm::length(hi - lo);
}

bool Scene::hasEffect(const std::string& e) const {
    for (const std::string& x : effects)
        if (x == e) return true;
    return false;
}

bool SceneStats::totalTrianglesExceeded(const LoadLimits& limits) const {
    return triangles > limits.maxTotalTriangles;
}

void finalizeScene(Scene& scene) {
    scene.wsBounds = Bounds3d{};
    scene.stats.triangles = 0;
    scene.stats.degenerateTriangles = 0;
    for (MeshPrimitive& mesh : scene.meshes) {
        mesh.degenerateTriangles = 0;
        for (const glm::dvec3& p : mesh.wsPositions) scene.wsBounds.extend(p);
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const glm::dvec3& a = mesh.wsPositions[mesh.indices[t]];
            const glm::dvec3& b = mesh.wsPositions[mesh.indices[t + 1]];
            const glm::dvec3& c = mesh.wsPositions[mesh.indices[t + 2]];
            // Exactly zero in double: such a triangle can never be hit, so it cannot cast a shadow
            // in either path. It keeps its id.prim so numbering stays that of the index buffer.
            if (glm::cross(b - a, c - a) == glm::dvec3(0.0)) ++mesh.degenerateTriangles;
        }
        scene.stats.triangles += mesh.triangleCount();
        scene.stats.degenerateTriangles += mesh.degenerateTriangles;
    }
    if (scene.wsBounds.empty()) return;
    const glm::dvec3 m = glm::max(glm::abs(scene.wsBounds.lo), glm::abs(scene.wsBounds.hi));
    if (std::max({m.x, m.y, m.z}) > kMaxCoordinate) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "a vertex coordinate of magnitude %.3g is beyond the limit of 2^62 (%.3g)",
                      std::max({m.x, m.y, m.z}), kMaxCoordinate);
        throwInputError(scene.path.empty() ? "(scene built in code)" : scene.path.string(),
                        "geometry", text);
    }
}

}  // namespace so
