// Case 3 (docs/hard-cases.md): closed meshes leak no shadow ray. A cube and an icosphere at seeded
// random rotations; rays aimed exactly at their (float) vertices and at points of their shared
// edges, traced through the oracle's own Embree scene (Accel: robust mode, origin filter) as the
// oracle traces them (rtcOccluded16, coherent, mask and id set; and rtcOccluded1). Every ray passes
// through the mesh's interior, so a ray that reports "unoccluded" leaked. The same rays in
// Embree's default (non-robust) mode are counted to show what the test can see. At image level,
// the oracle's shadows of the same meshes on a floor match the exact convex-polyhedron test.
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "case_scenes.h"
#include "core/channels.h"
#include "embree/embree_handles.h"
#include "hard_scenes.h"
#include "oracle/accel.h"
#include "test_scenes.h"

namespace so::test::hard {
namespace {

namespace ch = channels;

struct TestRay {
    glm::vec3 org, dir;
    float tfar;
};

struct MeshRays {
    std::vector<TestRay> rays;
    size_t vertexTargets = 0, edgeTargets = 0;
};

// Face planes (double, local frame): n.x <= d inside.
struct Plane {
    glm::dvec3 n;
    double d;
};

std::vector<Plane> facePlanes(const Accel& accel, size_t triangles) {
    std::vector<Plane> planes;
    for (size_t t = 0; t < triangles; ++t) {
        glm::dvec3 a, b, c;
        accel.triangle(0, unsigned(t), a, b, c);
        const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        planes.push_back({n, glm::dot(n, a)});
    }
    return planes;
}

bool inside(const std::vector<Plane>& planes, const glm::dvec3& p, double margin) {
    for (const Plane& pl : planes)
        if (glm::dot(pl.n, p) > pl.d - margin) return false;
    return true;
}

TestRay makeRay(const glm::dvec3& from, const glm::dvec3& to, double beyond) {
    const glm::dvec3 d = to - from;
    return {glm::vec3(from), glm::vec3(glm::normalize(d)), float(beyond * glm::length(d))};
}

// Targets: every vertex as Embree stores it (float), and `perEdge` points of every edge (its
// midpoint and random ones). Rays: from the interior centre through each target (one crossing,
// exactly there), and through pairs of targets whose midpoint is inside (two crossings).
MeshRays buildRays(const Accel& accel, const MeshPrimitive& mesh, const glm::dvec3& lsCenter,
                   double lsRadius, uint64_t seed) {
    std::vector<glm::dvec3> targets;
    MeshRays out;
    for (const glm::dvec3& ws : mesh.wsPositions)
        targets.push_back(glm::dvec3(glm::vec3(accel.frame().lsFromWs(ws))));
    out.vertexTargets = targets.size();
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t i = 0; i < mesh.indices.size(); ++i) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i - i % 3 + (i + 1) % 3];
        edges[std::minmax(a, b)] = 0;
    }
    uint64_t state = seed;
    auto uniform = [&state]() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1.0p-53;
    };
    for (const auto& [e, unused] : edges)
        for (int k = 0; k < 8; ++k) {
            const double t = k == 0 ? 0.5 : uniform();
            targets.push_back((1.0 - t) * targets[e.first] + t * targets[e.second]);
        }
    out.edgeTargets = targets.size() - out.vertexTargets;
    const std::vector<Plane> planes = facePlanes(accel, mesh.triangleCount());
    for (size_t i = 0; i < targets.size(); ++i) {
        out.rays.push_back(makeRay(lsCenter, targets[i], 2.0));
        for (int tries = 0, pairs = 0; tries < 20 && pairs < 3; ++tries) {
            const glm::dvec3& y = targets[size_t(uniform() * double(targets.size()))];
            if (!inside(planes, 0.5 * (targets[i] + y), 1e-3 * lsRadius)) continue;
            out.rays.push_back(makeRay(targets[i] + 0.5 * (targets[i] - y), y, 1.0 + 1.0 / 1.5));
            ++pairs;
        }
    }
    return out;
}

RTCRay toRtc(const TestRay& r) {
    RTCRay ray{};
    ray.org_x = r.org.x, ray.org_y = r.org.y, ray.org_z = r.org.z;
    ray.dir_x = r.dir.x, ray.dir_y = r.dir.y, ray.dir_z = r.dir.z;
    ray.tfar = r.tfar;
    ray.mask = 0xFFFFFFFFu;
    ray.id = kNoOriginTriangle;
    return ray;
}

size_t leaks1(RTCScene scene, const std::vector<TestRay>& rays) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    size_t leaks = 0;
    for (const TestRay& r : rays) {
        RTCRay ray = toRtc(r);
        rtcOccluded1(scene, &ctx, &ray);
        leaks += ray.tfar >= 0.0f;
    }
    return leaks;
}

// As the oracle's hard pass traces: 16-ray packets, coherent.
size_t leaks16(RTCScene scene, const std::vector<TestRay>& rays) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    size_t leaks = 0;
    for (size_t base = 0; base < rays.size(); base += 16) {
        alignas(64) RTCRay16 p{};
        alignas(64) int valid[16] = {};
        for (size_t k = 0; k < 16 && base + k < rays.size(); ++k) {
            const RTCRay r = toRtc(rays[base + k]);
            p.org_x[k] = r.org_x, p.org_y[k] = r.org_y, p.org_z[k] = r.org_z;
            p.dir_x[k] = r.dir_x, p.dir_y[k] = r.dir_y, p.dir_z[k] = r.dir_z;
            p.tfar[k] = r.tfar, p.mask[k] = r.mask, p.id[k] = r.id;
            valid[k] = -1;
        }
        rtcOccluded16(valid, scene, &ctx, &p);
        for (size_t k = 0; k < 16; ++k) leaks += valid[k] && p.tfar[k] >= 0.0f;
    }
    return leaks;
}

// The same float triangles in Embree's default mode (not robust), for comparison only.
EmbreeScene fastScene(const EmbreeDevice& device, const Accel& accel, size_t triangles) {
    EmbreeScene scene(device);
    EmbreeGeometry g(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(g.newBuffer(RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                               3 * sizeof(float), 3 * triangles));
    auto* ib = static_cast<uint32_t*>(
        g.newBuffer(RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles));
    for (size_t t = 0; t < triangles; ++t) {
        glm::dvec3 v[3];
        accel.triangle(0, unsigned(t), v[0], v[1], v[2]);
        for (int k = 0; k < 3; ++k) {
            for (int c = 0; c < 3; ++c) vb[9 * t + 3 * size_t(k) + size_t(c)] = float(v[k][c]);
            ib[3 * t + size_t(k)] = uint32_t(3 * t + size_t(k));
        }
    }
    rtcSetGeometryMask(g.get(), 0xFFFFFFFFu);
    g.commit();
    scene.attach(g, 0);
    scene.commit();
    return scene;
}

struct LeakTotals {
    size_t rays = 0, vertexTargets = 0, edgeTargets = 0, leaks1 = 0, leaks16 = 0, fastLeaks = 0;
};

void countLeaks(bool icosphere, uint64_t seed, const EmbreeDevice& device, LeakTotals& total) {
    const glm::dvec3 center(0.25, 0.5, -0.125);
    MeshPrimitive mesh = icosphere ? makeIcosphere(center, 1.0, 2, "icosphere")
                                   : makeBox(center - 0.75, center + 0.75, "cube");
    rotateMesh(mesh, randomRotation(seed), center);
    Scene scene;
    scene.meshes.push_back(mesh);
    finalizeScene(scene);
    const Accel accel(scene, device);
    const double lsRadius = accel.frame().lsLength(icosphere ? 1.0 : 0.75);
    const MeshRays r = buildRays(accel, mesh, accel.frame().lsFromWs(center), lsRadius, seed);
    setEmbreeFloatMode();
    total.rays += r.rays.size();
    total.vertexTargets += r.vertexTargets;
    total.edgeTargets += r.edgeTargets;
    total.leaks1 += leaks1(accel.rtcScene(), r.rays);
    total.leaks16 += leaks16(accel.rtcScene(), r.rays);
    const EmbreeScene fast = fastScene(device, accel, mesh.triangleCount());
    total.fastLeaks += leaks1(fast.get(), r.rays);
}

void checkNoLeaks(bool icosphere) {
    EmbreeDevice device;
    LeakTotals t;
    for (uint64_t seed = 1; seed <= 8; ++seed) countLeaks(icosphere, seed * 7919, device, t);
    std::printf(
        "[ hard ] closed %s, 8 rotations: %zu rays at %zu vertices and %zu edge points: "
        "%zu leaks (rtcOccluded1), %zu leaks (rtcOccluded16 coherent); Embree's default "
        "mode on the same rays: %zu leaks\n",
        icosphere ? "icosphere" : "cube", t.rays, t.vertexTargets, t.edgeTargets, t.leaks1,
        t.leaks16, t.fastLeaks);
    EXPECT_GT(t.rays, icosphere ? 50000u : 2000u);
    EXPECT_EQ(t.leaks1, 0u);
    EXPECT_EQ(t.leaks16, 0u);
    // The rays are hard: without the robust mode the same rays leak (measured: 78 of 4,863 on the
    // cube, 1,248 of 128,064 on the icosphere), so zero above is not for want of trying.
    EXPECT_GT(t.fastLeaks, 0u);
}

TEST(HardClosedMesh, CubeNoLeakThroughVerticesAndEdges) {
    checkNoLeaks(false);
}

TEST(HardClosedMesh, IcosphereNoLeakThroughVerticesAndEdges) {
    checkNoLeaks(true);
}

// The convex mesh's half-spaces n.x <= d + e, world space, double.
std::vector<Plane> worldPlanes(const MeshPrimitive& m) {
    std::vector<Plane> planes;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const glm::dvec3 &a = m.wsPositions[m.indices[t]], &b = m.wsPositions[m.indices[t + 1]],
                         &c = m.wsPositions[m.indices[t + 2]];
        const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        planes.push_back({n, glm::dot(n, a)});
    }
    return planes;
}

bool segmentHitsConvex(const glm::dvec3& p, const glm::dvec3& q, const std::vector<Plane>& planes,
                       double e) {
    double t0 = 0.0, t1 = 1.0;
    const glm::dvec3 d = q - p;
    for (const Plane& pl : planes) {
        const double num = pl.d + e - glm::dot(pl.n, p), den = glm::dot(pl.n, d);
        if (den == 0.0) {
            if (num < 0.0) return false;
        } else if (den > 0.0) {
            t1 = std::min(t1, num / den);
        } else {
            t0 = std::max(t0, num / den);
        }
    }
    return t0 <= t1;
}

// Image level: every floor pixel whose exact answer does not change within 2x the blind distance
// (faces moved in and out) must match it: no leak through the umbra, no false shadow.
void checkImage(bool icosphere, uint64_t seed, size_t& checked, size_t& umbra, size_t& wrong) {
    const ClosedMeshScene c = makeClosedMeshScene(icosphere, seed, 128);
    OracleResult r = runHard(c.scene);
    const std::vector<Plane> planes = worldPlanes(c.scene.meshes[1]);
    const double tol = 2.0 * r.stats.offsetPolicy.maxBlindDistance;
    const float* A = r.image.channel(ch::kHit);
    const float* mesh = r.image.channel(ch::kMeshId);
    const float* V = r.image.channel(ch::lightChannel("key", ch::kVisibility));
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (A[i] == 0.0f || mesh[i] != 0.0f) continue;
        glm::dvec3 p = hitPoint(r.image, i);
        p.y = 0.0;
        const bool occluded = segmentHitsConvex(p, c.wsLight, planes, 0.0);
        if (occluded != segmentHitsConvex(p, c.wsLight, planes, occluded ? -tol : tol)) continue;
        ++checked;
        umbra += occluded;
        wrong += V[i] != (occluded ? 0.0f : 1.0f);
    }
}

TEST(HardClosedMesh, ImageShadowsOfRotatedMeshesAreExact) {
    for (bool icosphere : {false, true}) {
        size_t checked = 0, umbra = 0, wrong = 0;
        for (uint64_t seed = 1; seed <= 4; ++seed)
            checkImage(icosphere, seed, checked, umbra, wrong);
        std::printf(
            "[ hard ] closed %s on a floor, 4 rotations: %zu floor px checked, %zu in the "
            "shadow, %zu differ from exact\n",
            icosphere ? "icosphere" : "cube", checked, umbra, wrong);
        EXPECT_EQ(wrong, 0u);
        EXPECT_GT(umbra, 1000u);
    }
}

}  // namespace
}  // namespace so::test::hard
