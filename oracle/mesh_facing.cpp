#include "oracle/mesh_facing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include <glm/geometric.hpp>

namespace so {

namespace {

using glm::dvec3;

bool finite(const dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool lexLess(const dvec3& a, const dvec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
}

// An edge by its positions, smaller first, which way its triangle runs it, and the triangle.
struct Edge {
    dvec3 lo, hi;
    bool forward;
    uint32_t triangle;
};

uint32_t root(std::vector<uint32_t>& parent, uint32_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
}

// The signed solid angle of triangle abc seen from the origin (Van Oosterom and Strackee).
double solidAngle(const dvec3& a, const dvec3& b, const dvec3& c) {
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double det = glm::dot(a, glm::cross(b, c));
    const double den =
        la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    return 2.0 * std::atan2(det, den);
}

// The mesh's edges, sorted so that the two runs of a shared edge are neighbours; false where a
// triangle is degenerate or not finite (then nothing of the mesh is taken as closed).
bool sortedEdges(const std::vector<dvec3>& P, const std::vector<uint32_t>& I,
                 std::vector<Edge>& edges) {
    edges.reserve(I.size());
    for (size_t t = 0; t < I.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t i = I[t + k], j = I[t + (k + 1) % 3];
            if (i >= P.size() || j >= P.size()) return false;
            const dvec3 &a = P[i], &b = P[j];
            if (!finite(a) || !finite(b) || a == b) return false;
            const bool forward = lexLess(a, b);
            edges.push_back({forward ? a : b, forward ? b : a, forward, uint32_t(t / 3)});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        if (x.lo != y.lo) return lexLess(x.lo, y.lo);
        if (x.hi != y.hi) return lexLess(x.hi, y.hi);
        return std::tie(x.forward, x.triangle) < std::tie(y.forward, y.triangle);
    });
    return true;
}

}  // namespace

std::vector<int8_t> triangleFacing(const std::vector<dvec3>& P, const std::vector<uint32_t>& I,
                                   const dvec3& lsEye) {
    const size_t triangles = I.size() / 3;
    std::vector<Edge> edges;
    if (triangles == 0 || I.size() % 3 != 0 || !sortedEdges(P, I, edges)) return {};
    // Parts: triangles joined across properly shared edges (one run each way); a triangle with
    // any other edge makes its part open.
    std::vector<uint32_t> parent(triangles);
    for (uint32_t t = 0; t < triangles; ++t) parent[t] = t;
    std::vector<uint8_t> open(triangles, 0);
    for (size_t e = 0; e < edges.size();) {
        size_t end = e + 1;
        while (end < edges.size() && edges[end].lo == edges[e].lo && edges[end].hi == edges[e].hi)
            ++end;
        if (end - e == 2 && !edges[e].forward && edges[e + 1].forward)
            parent[root(parent, edges[e].triangle)] = root(parent, edges[e + 1].triangle);
        else
            for (size_t k = e; k < end; ++k) open[edges[k].triangle] = 1;
        e = end;
    }
    // Per part: open or not, its winding number at the eye and its signed volume (6x).
    std::vector<uint8_t> partOpen(triangles, 0);
    std::vector<double> winding(triangles, 0.0), volume(triangles, 0.0);
    for (uint32_t t = 0; t < triangles; ++t) {
        const uint32_t r = root(parent, t);
        const dvec3 a = P[I[3 * t]] - lsEye, b = P[I[3 * t + 1]] - lsEye,
                    c = P[I[3 * t + 2]] - lsEye;
        partOpen[r] |= open[t];
        winding[r] += solidAngle(a, b, c) / (4.0 * std::numbers::pi);
        volume[r] += glm::dot(a, glm::cross(b, c));
    }
    std::vector<int8_t> keep(triangles, 0);
    for (uint32_t t = 0; t < triangles; ++t) {
        const uint32_t r = root(parent, t);
        if (partOpen[r] || volume[r] == 0.0) continue;
        const double s = volume[r] > 0.0 ? 1.0 : -1.0;
        // Outside (0): keep the side the entering crossing passes, s; inside (s): the other.
        if (std::abs(winding[r]) < 1e-3)
            keep[t] = int8_t(s);
        else if (std::abs(winding[r] - s) < 1e-3)
            keep[t] = int8_t(-s);
    }
    return keep;
}

MeshFacing meshFacing(const ExactScene& scene, const dvec3& lsEye) {
    MeshFacing facing(scene.meshCount());
    for (size_t m = 0; m < scene.meshCount(); ++m)
        if (!scene.alphaTested(uint32_t(m)))
            facing[m] =
                triangleFacing(scene.positions(uint32_t(m)), scene.indices(uint32_t(m)), lsEye);
    return facing;
}

}  // namespace so
