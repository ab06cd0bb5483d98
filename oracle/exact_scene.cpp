#include "oracle/exact_scene.h"

#include <glm/geometric.hpp>

namespace so {

namespace {

std::vector<std::vector<glm::dvec3>> toLocal(const Scene& scene, const LocalFrame& frame) {
    std::vector<std::vector<glm::dvec3>> out(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        out[m].reserve(scene.meshes[m].wsPositions.size());
        for (const glm::dvec3& ws : scene.meshes[m].wsPositions)
            out[m].push_back(frame.lsFromWs(ws));
    }
    return out;
}

std::vector<ExactTracer::MeshView> views(const std::vector<std::vector<glm::dvec3>>& ls,
                                         const Scene& scene) {
    std::vector<ExactTracer::MeshView> v;
    for (size_t m = 0; m < ls.size(); ++m)
        v.push_back({&ls[m], &scene.meshes[m].indices, scene.alphaTested(m)});
    return v;
}

}  // namespace

ExactScene::ExactScene(const Scene& scene, const LocalFrame& frame)
    : lsPositions_(toLocal(scene, frame)),
      alpha_(scene),
      tracer_(views(lsPositions_, scene), &alpha_) {
    for (const MeshPrimitive& m : scene.meshes) indices_.push_back(&m.indices);
}

std::array<glm::dvec3, 3> ExactScene::triangle(TriangleId id) const {
    const std::vector<glm::dvec3>& P = lsPositions_.at(id.mesh);
    const std::vector<uint32_t>& I = *indices_.at(id.mesh);
    return {P[I.at(3 * size_t(id.prim))], P[I.at(3 * size_t(id.prim) + 1)],
            P[I.at(3 * size_t(id.prim) + 2)]};
}

glm::dvec3 ExactScene::point(TriangleId id, double u, double v) const {
    const auto [a, b, c] = triangle(id);
    return (1.0 - u - v) * a + u * b + v * c;
}

glm::dvec3 ExactScene::normal(TriangleId id, const glm::dvec3& facing) const {
    const auto [a, b, c] = triangle(id);
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    return glm::dot(n, facing) < 0.0 ? -n : n;
}

}  // namespace so
