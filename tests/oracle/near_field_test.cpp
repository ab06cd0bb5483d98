// The near field's shortcut for hard lights (oracle/near_field.h, nearSineBound): a lane whose
// cosine against its own normal exceeds the slot's bound keeps Embree's answer, so the bound must
// never rule out a triangle that a segment can reach. Checked here against the criterion itself,
// written out again from docs/oracle.md ("The near field"): a segment crossing T's plane matters
// where its crossing comes within kReach (1 + 1 / sine) of T; one that does not cross matters
// unless p and the ray's origin both lie above the plane, the origin beyond Embree's rounding; a
// meeting within kNearContact of p is contact at the receiver's own point, no occluder.
// On creased height fields (ridges and valleys at random angles, steep and shallow), at points
// next to edges and vertices, in directions from straight up to a hair above the horizon.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/scene.h"
#include "embree/embree_handles.h"
#include "oracle/accel.h"
#include "oracle/exact_tracer.h"
#include "oracle/near_field.h"
#include "oracle/offset.h"

namespace so {
namespace {

// A 24 x 24 height field over [-1, 1]^2 with random heights up to `amplitude`: creases of every
// angle up to about atan(2 amplitude / 0.083).
Scene creasedField(uint32_t seed, double amplitude) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> height(-amplitude, amplitude);
    const int n = 24;
    MeshPrimitive m;
    m.name = "field";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.wsPositions.push_back({-1.0 + 2.0 * i / n, height(rng), -1.0 + 2.0 * j / n});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1),
                           d = c + 1;
            for (uint32_t v : {a, c, b, b, c, d}) m.indices.push_back(v);
        }
    Scene s;
    s.meshes = {m};
    finalizeScene(s);
    return s;
}

// The criterion, for the segment from p along the unit direction dir (to infinity).
bool reaches(const NearTriangle& t, const glm::dvec3& origin, const glm::dvec3& m0,
             const glm::dvec3& dir) {
    const double kReach = kLsOriginOffset + 4.0 / 16777216.0;
    const double along = glm::dot(t.n, dir);
    if (std::fabs(t.side) <= kNearContact * std::fabs(along)) return false;  // contact at p
    if (t.side * along < 0.0) {                                              // crosses the plane
        const glm::dvec3 x = t.p - (t.side / along) * dir;
        return exact::pointTriangle(x, t.a, t.b, t.c) <= kReach * (1.0 + 1.0 / std::fabs(along));
    }
    const double sign = glm::dot(t.n, m0) < 0.0 ? -1.0 : 1.0;
    const double hp = sign * t.side, ho = sign * glm::dot(t.n, origin - t.a);
    return !(hp > 0.0 && ho > kReach - kLsOriginOffset);
}

// The point at barycentrics (u, v) of triangle `prim`, and its unit normal turned up (the lit
// side).
struct FieldPoint {
    glm::dvec3 p, m0;
};
FieldPoint fieldPoint(const Accel& accel, unsigned prim, double u, double v) {
    glm::dvec3 a, b, c;
    accel.triangle(0, prim, a, b, c);
    glm::dvec3 m0 = glm::normalize(glm::cross(b - a, c - a));
    if (m0.y < 0.0) m0 = -m0;
    return {(1.0 - u - v) * a + u * b + v * c, m0};
}

TEST(NearField, SineBoundNeverRulesOutATriangleASegmentReaches) {
    EmbreeDevice device("threads=1");
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    uint64_t slots = 0, ruledOut = 0, checked = 0, bounded = 0;
    for (uint32_t seed = 1; seed <= 3; ++seed) {
        const Scene scene = creasedField(seed, 0.08 / std::pow(8.0, double(seed - 1)));
        const Accel accel(scene, device);
        const unsigned triangles = unsigned(scene.meshes[0].triangleCount());
        for (int sample = 0; sample < 4000; ++sample) {
            const unsigned prim = unsigned(unit(rng) * triangles) % triangles;
            // Points next to an edge or a vertex: one barycentric (or two) within 1e-4 of 0.
            double u = unit(rng), v = unit(rng) * (1.0 - u);
            if (sample % 3 == 0) u = 1e-4 * unit(rng);
            if (sample % 3 == 1) v = 1e-4 * unit(rng), u = std::min(u, 1e-4 * unit(rng));
            const auto [p, m0] = fieldPoint(accel, prim, u, v);
            std::vector<uint32_t> ids;
            std::vector<NearTriangle> near;
            appendNearField(accel, p, 0, prim, ids, near);
            if (near.empty()) continue;
            ++slots;
            const glm::dvec3 origin(errorBoundOrigin(p, m0));
            const float bound = nearSineBound(near.data(), near.size(), m0, origin);
            bounded += std::isfinite(bound);
            for (int k = 0; k < 64; ++k) {
                // Elevations from 90 degrees down to 1e-4 radians over the horizon of m0.
                const double elevation = std::pow(10.0, -4.0 * unit(rng)) * 1.5707963;
                const double azimuth = 6.283185307 * unit(rng);
                glm::dvec3 e1 = glm::normalize(glm::cross(m0, glm::dvec3(1, 0, 0)));
                const glm::dvec3 e2 = glm::cross(m0, e1);
                const glm::dvec3 dir = glm::normalize(
                    std::sin(elevation) * m0 +
                    std::cos(elevation) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2));
                if (!(glm::dot(m0, dir) > double(bound))) continue;
                ++ruledOut;
                for (const NearTriangle& t : near) {
                    ++checked;
                    EXPECT_FALSE(reaches(t, origin, m0, dir))
                        << "seed " << seed << " triangle " << prim << " bound " << bound
                        << " cosine " << glm::dot(m0, dir);
                }
            }
        }
    }
    std::printf(
        "[ near ] %llu slots with a near field (%llu with a finite bound), %llu lanes "
        "ruled out, %llu triangles checked\n",
        (unsigned long long)slots, (unsigned long long)bounded, (unsigned long long)ruledOut,
        (unsigned long long)checked);
    // The check must have had work: most slots next to a crease get a finite bound.
    EXPECT_GT(slots, 3000u);
    EXPECT_GT(bounded, slots / 2);
    EXPECT_GT(checked, 50000u);
}

// The criterion for the segment from p to the light's point q.
bool reachesPoint(const NearTriangle& t, const glm::dvec3& origin, const glm::dvec3& q) {
    const double kReach = kLsOriginOffset + 4.0 / 16777216.0;
    const glm::dvec3 d = q - t.p;
    const double along = glm::dot(t.n, d);
    if (std::fabs(t.side) <= kNearContact * std::fabs(along) / glm::length(d)) return false;
    if (t.side * along < 0.0 && std::fabs(t.side) < std::fabs(along)) {  // crosses before q
        const glm::dvec3 x = t.p - (t.side / along) * d;
        return exact::pointTriangle(x, t.a, t.b, t.c) <=
               kReach * (1.0 + glm::length(d) / std::fabs(along));
    }
    const double ho = glm::dot(t.n, origin - t.a);
    return !(ho * t.side > 0.0 && std::fabs(ho) > kReach - kLsOriginOffset);
}

// The same for an area light's pixel (appendRelevant): rect lights anywhere over the field, from
// high above to cut by the surface's plane, and every triangle the test leaves to Embree checked
// against segments to 64 points of the light.
TEST(NearField, AreaRelevanceNeverDropsATriangleASegmentReaches) {
    EmbreeDevice device("threads=1");
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    uint64_t kept = 0, dropped = 0, checked = 0;
    for (uint32_t seed = 1; seed <= 3; ++seed) {
        const Scene scene = creasedField(seed, 0.08 / std::pow(8.0, double(seed - 1)));
        const Accel accel(scene, device);
        const unsigned triangles = unsigned(scene.meshes[0].triangleCount());
        for (int sample = 0; sample < 1500; ++sample) {
            const unsigned prim = unsigned(unit(rng) * triangles) % triangles;
            double u = 1e-4 * unit(rng), v = unit(rng) * (1.0 - u);
            if (sample % 2) std::swap(u, v);
            const auto [p, m0] = fieldPoint(accel, prim, u, v);
            NearFields f;
            f.begin = {0};
            appendNearField(accel, p, 0, prim, f.ids, f.triangles);
            f.begin.push_back(uint32_t(f.ids.size()));
            if (f.ids.empty()) continue;
            // A rect light: its centre up to 2 units away at elevations from -5 to 90 degrees.
            const double elevation = (-5.0 + 95.0 * unit(rng) * unit(rng)) * 3.14159265 / 180.0;
            const double azimuth = 6.283185307 * unit(rng), range = 0.05 + 2.0 * unit(rng);
            const glm::dvec3 centre =
                p + range * glm::dvec3(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                                       std::cos(elevation) * std::sin(azimuth));
            const glm::dvec3 eu = (0.02 + 0.3 * unit(rng)) * glm::dvec3(1, 0, 0),
                             ev = (0.02 + 0.3 * unit(rng)) * glm::dvec3(0, 0.3, 1);
            NearTarget target;
            target.count = 4;
            for (int k = 0; k < 4; ++k)
                target.points[k] = centre + (k & 1 ? eu : -eu) + (k & 2 ? ev : -ev);
            const glm::dvec3 origin(errorBoundOrigin(p, m0));
            std::vector<uint32_t> ids;
            std::vector<NearTriangle> relevant;
            appendRelevant(f, 0, f.begin[1], target, origin, ids, relevant);
            kept += relevant.size();
            for (size_t i = 0; i < f.triangles.size(); ++i) {
                if (std::find(ids.begin(), ids.end(), f.ids[i]) != ids.end()) continue;
                ++dropped;
                for (int k = 0; k < 64; ++k) {
                    const glm::dvec3 q =
                        centre + (2.0 * unit(rng) - 1.0) * eu + (2.0 * unit(rng) - 1.0) * ev;
                    ++checked;
                    EXPECT_FALSE(reachesPoint(f.triangles[i], origin, q))
                        << "seed " << seed << " triangle " << prim;
                }
            }
        }
    }
    std::printf(
        "[ near ] area lights: %llu near triangles kept, %llu left to Embree, %llu "
        "segments checked\n",
        (unsigned long long)kept, (unsigned long long)dropped, (unsigned long long)checked);
    EXPECT_GT(dropped, 1000u);
    EXPECT_GT(kept, 100u);
}

}  // namespace
}  // namespace so
