#include "raster_compare/gl/volumes/receiver_plane.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace so {

glm::dmat4 planarProjection(const glm::dvec4& P, const glm::dvec4& L) {
    glm::dmat4 M(glm::dot(P, L));
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) M[col][row] -= L[row] * P[col];
    return M;
}

glm::dmat4 flattenOnto(const glm::dvec4& P) {
    const glm::dvec4 n(P.x, P.y, P.z, 0.0);
    glm::dmat4 M(1.0);
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) M[col][row] -= n[row] * P[col];
    return M;
}

std::optional<ReceiverPlane> planeOfMesh(const MeshPrimitive& mesh, const LocalFrame& frame) {
    if (mesh.indices.size() < 3) return std::nullopt;
    glm::dvec3 lsNormal(0.0), lsOnPlane(0.0);
    double best = 0.0, wsArea = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 a = mesh.wsPositions[mesh.indices[t]],
                         b = mesh.wsPositions[mesh.indices[t + 1]],
                         c = mesh.wsPositions[mesh.indices[t + 2]];
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double len = glm::length(n);
        wsArea += 0.5 * len;
        if (len > best) {
            best = len;
            lsNormal = n / len;
            lsOnPlane = frame.lsFromWs(a);
        }
    }
    if (!(best > 0.0)) return std::nullopt;
    Bounds3d lsBounds;
    for (const glm::dvec3& ws : mesh.wsPositions) lsBounds.extend(frame.lsFromWs(ws));
    const double extent = glm::length(lsBounds.hi - lsBounds.lo);
    const double d = -glm::dot(lsNormal, lsOnPlane);
    for (uint32_t i : mesh.indices)
        if (std::fabs(glm::dot(lsNormal, frame.lsFromWs(mesh.wsPositions[i])) + d) > 1e-6 * extent)
            return std::nullopt;
    return ReceiverPlane{-1, glm::dvec4(lsNormal, d), wsArea};
}

ReceiverPlane findReceiver(const Scene& scene, const LocalFrame& frame, int requested,
                           const std::string& technique) {
    const std::string where = "technique " + technique;
    if (requested >= int(scene.meshes.size()))
        throwInputError(where, "receiver",
                        "mesh " + std::to_string(requested) + " does not exist (the scene has " +
                            std::to_string(scene.meshes.size()) + ")");
    if (requested >= 0) {
        std::optional<ReceiverPlane> p = planeOfMesh(scene.meshes[size_t(requested)], frame);
        if (!p)
            throwInputError(where, "receiver",
                            "mesh " + std::to_string(requested) + " (" +
                                scene.meshes[size_t(requested)].name + ") is not planar");
        p->mesh = requested;
        return *p;
    }
    std::optional<ReceiverPlane> best;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        std::optional<ReceiverPlane> p = planeOfMesh(scene.meshes[m], frame);
        if (p && (!best || p->area > best->area)) {
            best = p;
            best->mesh = int(m);
        }
    }
    if (!best)
        throwInputError(where, "receiver", "the scene has no planar mesh to receive shadows");
    return *best;
}

}  // namespace so
