#include "raster_compare/gl/volumes/shadow_volume_geometry.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace so {

namespace {

// A casting triangle: its corners' ids and positions, wound to face the light (`flipped`: the
// mesh's winding is the other way).
struct Caster {
    uint32_t id[3];
    glm::dvec3 p[3];
    bool flipped = false;
    size_t triangle = 0;  // its index in WeldedScene::triangles
};

// Calls f(Caster) for every triangle that casts: not degenerate, not edge-on to the light.
template <typename F>
void forEachCaster(const WeldedScene& scene, const glm::dvec4& lsLight, F&& f) {
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
        const std::array<uint32_t, 3>& t = scene.triangles[i];
        Caster c;
        c.triangle = i;
        for (int k = 0; k < 3; ++k) {
            c.id[k] = t[size_t(k)];
            c.p[k] = scene.lsPositions[t[size_t(k)]];
        }
        const glm::dvec3 n = glm::cross(c.p[1] - c.p[0], c.p[2] - c.p[0]);
        const glm::dvec3 toLight =
            lsLight.w != 0.0 ? glm::dvec3(lsLight) - c.p[0] : -glm::dvec3(lsLight);
        const double s = glm::dot(n, toLight);
        if (s == 0.0 || !(glm::dot(n, n) > 0.0)) continue;
        c.flipped = s < 0.0;
        if (c.flipped) {
            std::swap(c.p[1], c.p[2]);
            std::swap(c.id[1], c.id[2]);
        }
        f(c);
    }
}

struct PositionKey {
    std::array<uint64_t, 3> bits;
    bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
    size_t operator()(const PositionKey& k) const {
        uint64_t h = 1469598103934665603ull;
        for (uint64_t b : k.bits) h = (h ^ b) * 1099511628211ull;
        return size_t(h);
    }
};

// Per undirected edge (lo id, hi id), the signed count of the casters that run along it from lo
// to hi (+1) or back (-1).
struct EdgeCounts {
    std::unordered_map<uint64_t, int> count;
    void add(uint32_t ia, uint32_t ib) {
        if (ia == ib) return;
        const bool forward = ia < ib;
        const uint64_t key = forward ? (uint64_t(ia) << 32 | ib) : (uint64_t(ib) << 32 | ia);
        count[key] += forward ? 1 : -1;
    }
};

void pushFinite(std::vector<float>& v, const glm::dvec3& p) {
    v.insert(v.end(), {float(p.x), float(p.y), float(p.z), 1.0f});
}

// The point p seen from the light, at infinity.
void pushInfinite(std::vector<float>& v, const glm::dvec3& p, const glm::dvec4& lsLight) {
    const glm::dvec3 d = lsLight.w != 0.0 ? p - glm::dvec3(lsLight) : glm::dvec3(lsLight);
    v.insert(v.end(), {float(d.x), float(d.y), float(d.z), 0.0f});
}

}  // namespace

WeldedScene WeldedScene::build(const Scene& scene, const LocalFrame& frame) {
    WeldedScene w;
    std::unordered_map<PositionKey, uint32_t, PositionHash> ids;
    for (const MeshPrimitive& m : scene.meshes) {
        w.meshFirstTriangle.push_back(w.triangles.size());
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            std::array<uint32_t, 3> tri;
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 p = frame.lsFromWs(m.wsPositions[m.indices[t + size_t(k)]]);
                const PositionKey key{{std::bit_cast<uint64_t>(p.x), std::bit_cast<uint64_t>(p.y),
                                       std::bit_cast<uint64_t>(p.z)}};
                const auto [it, added] = ids.try_emplace(key, uint32_t(w.lsPositions.size()));
                if (added) w.lsPositions.push_back(p);
                tri[size_t(k)] = it->second;
            }
            w.triangles.push_back(tri);
        }
    }
    return w;
}

ShadowVolumeGeometry buildShadowVolumes(const WeldedScene& scene, const glm::dvec4& lsLight) {
    ShadowVolumeGeometry g;
    EdgeCounts edges;
    std::vector<float> flippedCaps;
    forEachCaster(scene, lsLight, [&](const Caster& c) {
        ++g.casters;
        // In the mesh's own vertex order (undoing the flip).
        std::vector<float>& caps = c.flipped ? flippedCaps : g.nearCaps;
        for (int k : c.flipped ? std::array<int, 3>{0, 2, 1} : std::array<int, 3>{0, 1, 2})
            caps.insert(caps.end(), {float(c.p[k].x), float(c.p[k].y), float(c.p[k].z)});
        g.nearCapsFlipped += c.flipped ? 1 : 0;
        for (int k : {0, 2, 1}) pushInfinite(g.farCaps, c.p[k], lsLight);
        for (int k = 0; k < 3; ++k) edges.add(c.id[k], c.id[(k + 1) % 3]);
    });
    g.nearCaps.insert(g.nearCaps.end(), flippedCaps.begin(), flippedCaps.end());
    // Edges in id order, so the geometry does not depend on the hash map's iteration order.
    std::vector<std::pair<uint64_t, int>> kept;
    for (const auto& [key, n] : edges.count)
        if (n != 0) kept.emplace_back(key, n);
    std::sort(kept.begin(), kept.end());
    for (const auto& [key, n] : kept) {
        glm::dvec3 a = scene.lsPositions[key >> 32], b = scene.lsPositions[key & 0xffffffffu];
        if (n < 0) std::swap(a, b);
        // The quad on edge a -> b of a light-facing triangle, wound to face out of the volume:
        // (a, a at infinity, b at infinity) and (a, b at infinity, b).
        for (int q = 0; q < std::abs(n); ++q) {
            pushFinite(g.sides, a);
            pushInfinite(g.sides, a, lsLight);
            pushInfinite(g.sides, b, lsLight);
            pushFinite(g.sides, a);
            pushInfinite(g.sides, b, lsLight);
            pushFinite(g.sides, b);
            ++g.quads;
        }
    }
    return g;
}

std::vector<std::array<uint32_t, 2>> silhouetteEdges(const WeldedScene& scene,
                                                     const glm::dvec4& lsLight, int skipMesh) {
    size_t skipBegin = 0, skipEnd = 0;
    if (skipMesh >= 0 && size_t(skipMesh) < scene.meshFirstTriangle.size()) {
        skipBegin = scene.meshFirstTriangle[size_t(skipMesh)];
        skipEnd = size_t(skipMesh) + 1 < scene.meshFirstTriangle.size()
                      ? scene.meshFirstTriangle[size_t(skipMesh) + 1]
                      : scene.triangles.size();
    }
    EdgeCounts edges;
    forEachCaster(scene, lsLight, [&](const Caster& c) {
        if (c.triangle >= skipBegin && c.triangle < skipEnd) return;
        for (int k = 0; k < 3; ++k) edges.add(c.id[k], c.id[(k + 1) % 3]);
    });
    std::vector<std::array<uint32_t, 2>> kept;
    for (const auto& [key, n] : edges.count) {
        if (n == 0) continue;
        const uint32_t lo = uint32_t(key >> 32), hi = uint32_t(key & 0xffffffffu);
        kept.push_back(n > 0 ? std::array<uint32_t, 2>{lo, hi} : std::array<uint32_t, 2>{hi, lo});
    }
    std::sort(kept.begin(), kept.end());
    return kept;
}

int volumesContaining(const WeldedScene& scene, const glm::dvec4& lsLight,
                      const glm::dvec3& lsEye) {
    // Moller-Trumbore in double; the segment's open interior for a point light, the whole ray for
    // a directional one.
    const bool point = lsLight.w != 0.0;
    const glm::dvec3 d = point ? glm::dvec3(lsLight) - lsEye : -glm::dvec3(lsLight);
    int n = 0;
    forEachCaster(scene, lsLight, [&](const Caster& c) {
        const glm::dvec3 e1 = c.p[1] - c.p[0], e2 = c.p[2] - c.p[0];
        const glm::dvec3 pv = glm::cross(d, e2);
        const double det = glm::dot(e1, pv);
        if (det == 0.0) return;
        const double inv = 1.0 / det;
        const glm::dvec3 tv = lsEye - c.p[0];
        const double u = glm::dot(tv, pv) * inv;
        if (u < 0.0 || u > 1.0) return;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double v = glm::dot(d, qv) * inv;
        if (v < 0.0 || u + v > 1.0) return;
        const double t = glm::dot(e2, qv) * inv;
        if (t > 0.0 && (!point || t < 1.0)) ++n;
    });
    return n;
}

}  // namespace so
