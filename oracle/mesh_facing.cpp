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

// An edge by its ends' position ids (positionIds), smaller first, packed in one key; which way its
// triangle runs it, and the triangle.
struct Edge {
    uint64_t ends;
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

// Per vertex, the rank of its position among the mesh's distinct finite positions (lexLess
// order), so that equal positions share an id and ids compare as their positions do; kNotFinite
// for a position that is not finite.
constexpr uint32_t kNotFinite = UINT32_MAX;
std::vector<uint32_t> positionIds(const std::vector<dvec3>& P) {
    std::vector<uint32_t> order, ids(P.size(), kNotFinite);
    order.reserve(P.size());
    for (uint32_t i = 0; i < P.size(); ++i)
        if (finite(P[i])) order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return lexLess(P[a], P[b]); });
    uint32_t id = 0;
    for (size_t k = 0; k < order.size(); ++k) {
        id += k > 0 && P[order[k]] != P[order[k - 1]];
        ids[order[k]] = id;
    }
    return ids;
}

// The mesh's edges, sorted so that the runs of a shared edge are neighbours; false where a
// triangle is degenerate or not finite (then nothing of the mesh is taken as closed). Sorting
// 32-bit ids rather than positions: the same groups, several times faster.
bool sortedEdges(const std::vector<dvec3>& P, const std::vector<uint32_t>& I,
                 std::vector<Edge>& edges) {
    const std::vector<uint32_t> ids = positionIds(P);
    edges.reserve(I.size());
    for (size_t t = 0; t < I.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t i = I[t + k], j = I[t + (k + 1) % 3];
            if (i >= P.size() || j >= P.size() || ids[i] == kNotFinite || ids[j] == kNotFinite ||
                ids[i] == ids[j])
                return false;
            const bool forward = ids[i] < ids[j];
            const uint64_t lo = std::min(ids[i], ids[j]), hi = std::max(ids[i], ids[j]);
            edges.push_back({lo << 32 | hi, forward, uint32_t(t / 3)});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        return std::tie(x.ends, x.forward, x.triangle) < std::tie(y.ends, y.forward, y.triangle);
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
        while (end < edges.size() && edges[end].ends == edges[e].ends) ++end;
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
