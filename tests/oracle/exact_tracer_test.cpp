// The exact double-precision re-tracer (oracle/exact_tracer.h): its BVH against brute force over
// the same per-triangle tests, and its robustness margins against closed forms.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "oracle/exact_tracer.h"

namespace so {
namespace {

using glm::dvec3;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Meshes owned by the test, viewed by the tracer.
struct Scene {
    struct Mesh {
        std::vector<dvec3> positions;
        std::vector<uint32_t> indices;
    };
    std::vector<Mesh> meshes;

    void addTriangle(size_t mesh, const dvec3& a, const dvec3& b, const dvec3& c) {
        if (meshes.size() <= mesh) meshes.resize(mesh + 1);
        Mesh& m = meshes[mesh];
        for (const dvec3& p : {a, b, c}) {
            m.indices.push_back(static_cast<uint32_t>(m.positions.size()));
            m.positions.push_back(p);
        }
    }
    std::vector<ExactTracer::MeshView> views() const {
        std::vector<ExactTracer::MeshView> v;
        for (const Mesh& m : meshes) v.push_back({&m.positions, &m.indices});
        return v;
    }
    template <class F>
    void forEach(F&& f) const {
        for (size_t m = 0; m < meshes.size(); ++m) {
            const Mesh& mesh = meshes[m];
            for (size_t p = 0; p < mesh.indices.size() / 3; ++p)
                f(TriangleId{uint32_t(m), uint32_t(p)}, mesh.positions[mesh.indices[3 * p]],
                  mesh.positions[mesh.indices[3 * p + 1]], mesh.positions[mesh.indices[3 * p + 2]]);
        }
    }
};

bool idLess(const TriangleId& a, const TriangleId& b) {
    return a.mesh != b.mesh ? a.mesh < b.mesh : a.prim < b.prim;
}

dvec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> n;
    dvec3 v;
    do v = {n(rng), n(rng), n(rng)};
    while (glm::dot(v, v) < 1e-6);
    return glm::normalize(v);
}

// Random triangles of size ~`size` in [-1, 1]^3 over three meshes, some of them degenerate, and
// some pairs sharing an edge (where a watertight test matters).
Scene randomSoup(std::mt19937_64& rng, int count, double size) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Scene s;
    for (int i = 0; i < count; ++i) {
        const size_t mesh = static_cast<size_t>(i % 3);
        const dvec3 c{u(rng), u(rng), u(rng)};
        const dvec3 a = c + size * randomUnit(rng), b = c + size * randomUnit(rng);
        dvec3 p = c + size * randomUnit(rng);
        if (i % 50 == 7) p = a + 0.5 * (b - a);  // collinear (maybe not exactly, after rounding)
        if (i % 50 == 8) p = a;                  // exactly degenerate
        s.addTriangle(mesh, a, b, p);
        if (i % 10 == 3) s.addTriangle(mesh, b, a, c - size * randomUnit(rng)), ++i;
    }
    return s;
}

ExactTracer::Hit bruteClosest(const Scene& s, const dvec3& o, const dvec3& d, double tMin,
                              double tMax, TriangleId skip) {
    ExactTracer::Hit best;
    s.forEach([&](TriangleId id, const dvec3& a, const dvec3& b, const dvec3& c) {
        double t, b1, b2;
        if (id == skip || !exact::rayTriangle(o, d, tMin, tMax, a, b, c, t, b1, b2)) return;
        if (best.found && (t > best.t || (t == best.t && !idLess(id, best.id)))) return;
        best = {true, t, id, b1, b2};
    });
    return best;
}

// ExactTracer::segment() by brute force (finite tMax), from the same per-triangle function.
ExactTracer::SegmentQuery bruteSegment(const Scene& s, const dvec3& o, const dvec3& d, double tMax,
                                       TriangleId skip, double tolAbs, double tolPerT) {
    ExactTracer::SegmentQuery q;
    const double reach = tolAbs + tolPerT * tMax;
    double bestSlack = kInf;
    s.forEach([&](TriangleId id, const dvec3& a, const dvec3& b, const dvec3& c) {
        if (id == skip) return;
        const exact::SegmentTriangle st = exact::segmentTriangle(o, d, tMax, true, a, b, c);
        if (st.crossed &&
            (st.tHit < q.firstHitT || (st.tHit == q.firstHitT && idLess(id, q.firstHit))))
            q.firstHitT = st.tHit, q.firstHit = id;
        if (!st.crossed && st.margin > reach) return;
        const double slack = st.margin - (tolAbs + tolPerT * st.t);
        if (slack < 0) q.ambiguous = true;
        if (slack < bestSlack || (slack == bestSlack && idLess(id, q.nearest)))
            bestSlack = slack, q.margin = st.margin, q.marginT = st.t, q.nearest = id;
    });
    q.occluded = q.firstHitT < kInf;
    return q;
}

// ---------------------------------------------------------------------------------------------
// Building blocks

TEST(ExactGeometry, SegmentSegmentClosedForms) {
    // Skew, crossing over each other in the interior: distance 2 at s = 0.25.
    exact::Approach a = exact::segmentSegment({-1, 0, 0}, {3, 0, 0}, {0, -1, 2}, {0, 1, 2});
    EXPECT_DOUBLE_EQ(a.dist, 2.0);
    EXPECT_DOUBLE_EQ(a.s, 0.25);
    // Parallel and overlapping: distance 1 wherever.
    a = exact::segmentSegment({0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 1, 0});
    EXPECT_DOUBLE_EQ(a.dist, 1.0);
    // Collinear, disjoint: the gap between the ends.
    a = exact::segmentSegment({0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {5, 0, 0});
    EXPECT_DOUBLE_EQ(a.dist, 2.0);
    EXPECT_DOUBLE_EQ(a.s, 1.0);
    // The closest point lies beyond an end of one segment: end to segment.
    a = exact::segmentSegment({0, 0, 0}, {1, 0, 0}, {2, -1, 1}, {2, 1, 1});
    EXPECT_DOUBLE_EQ(a.dist, std::sqrt(2.0));
    // Degenerate: a point against a segment, and two points.
    a = exact::segmentSegment({0, 3, 0}, {0, 3, 0}, {-1, 0, 0}, {1, 0, 0});
    EXPECT_DOUBLE_EQ(a.dist, 3.0);
    a = exact::segmentSegment({0, 0, 0}, {0, 0, 0}, {3, 4, 0}, {3, 4, 0});
    EXPECT_DOUBLE_EQ(a.dist, 5.0);
}

TEST(ExactGeometry, PointTriangleRegions) {
    const dvec3 a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
    EXPECT_DOUBLE_EQ(exact::pointTriangle({0.5, 0.5, 3}, a, b, c), 3.0);         // face
    EXPECT_DOUBLE_EQ(exact::pointTriangle({1, -1, 0}, a, b, c), 1.0);            // edge ab
    EXPECT_DOUBLE_EQ(exact::pointTriangle({2, 2, 0}, a, b, c), std::sqrt(2.0));  // edge bc
    EXPECT_DOUBLE_EQ(exact::pointTriangle({-3, -4, 0}, a, b, c), 5.0);           // vertex a
    EXPECT_EQ(exact::pointTriangle({1, 0, 0}, a, b, c), 0.0);                    // on the edge
    // A degenerate triangle is its edges.
    EXPECT_DOUBLE_EQ(exact::pointTriangle({1, 1, 0}, a, b, {1, 0, 0}), 1.0);
}

TEST(ExactGeometry, SharedEdgeIsWatertight) {
    // Rays aimed at points of the shared diagonal of a (nearly) planar quad in a plane aligned
    // with no axis: each must hit at least one of the two triangles. (Where the two triangles face
    // the ray oppositely the diagonal is a silhouette and a miss is right, so those are left out.)
    const dvec3 p0{0.1, 0.2, 0.3}, p1{1.3, 0.25, 0.7}, p2{1.1, 1.4, 0.1}, p3 = p0 + (p2 - p1);
    const dvec3 n1 = glm::cross(p1 - p0, p2 - p0), n2 = glm::cross(p2 - p0, p3 - p0);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int tested = 0;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 target = p0 + u(rng) * (p2 - p0);
        const dvec3 o = target + 3.0 * randomUnit(rng);
        const dvec3 d = target - o;
        if (glm::dot(d, n1) * glm::dot(d, n2) <= 1e-6) continue;
        double t, b1, b2;
        const bool h1 = exact::rayTriangle(o, d, 0, 2, p0, p1, p2, t, b1, b2);
        const bool h2 = exact::rayTriangle(o, d, 0, 2, p0, p2, p3, t, b1, b2);
        ASSERT_TRUE(h1 || h2) << i;
        ++tested;
    }
    EXPECT_GT(tested, 15000);
}

TEST(ExactGeometry, FanAroundAVertexIsWatertight) {
    // Rays aimed exactly at the shared vertex of a planar fan in a slanted plane: one of the
    // triangles must be hit.
    const dvec3 centre{0.3, -0.2, 0.7}, e1{1.0, 0.2, 0.3}, e2{-0.1, 0.9, 0.4};
    std::vector<dvec3> rim;
    for (int k = 0; k < 7; ++k) {
        const double a = 2.0 * 3.141592653589793 * (k + 0.1 * k * k) / 8.8;
        rim.push_back(centre + std::cos(a) * e1 + std::sin(a) * e2);
    }
    const dvec3 n = glm::cross(e1, e2);
    std::mt19937_64 rng(11);
    int tested = 0;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 o = centre + 2.0 * randomUnit(rng);
        const dvec3 d = centre - o;
        if (std::abs(glm::dot(glm::normalize(d), glm::normalize(n))) < 1e-3) continue;
        bool hit = false;
        for (size_t k = 0; k < rim.size() && !hit; ++k) {
            double t, b1, b2;
            hit = exact::rayTriangle(o, d, 0, 2, centre, rim[k], rim[(k + 1) % rim.size()], t, b1,
                                     b2);
        }
        ASSERT_TRUE(hit) << i;
        ++tested;
    }
    EXPECT_GT(tested, 19000);
}

// ---------------------------------------------------------------------------------------------
// 1. closestHit / occluded against brute force

TEST(ExactTracer, RaysMatchBruteForce) {
    std::mt19937_64 rng(12345);
    const Scene s = randomSoup(rng, 2000, 0.15);
    const ExactTracer tracer(s.views());
    std::vector<TriangleId> ids;
    s.forEach([&](TriangleId id, const dvec3&, const dvec3&, const dvec3&) { ids.push_back(id); });
    ASSERT_EQ(tracer.triangleCount(), ids.size());

    std::uniform_real_distribution<double> u(-1.5, 1.5), u01(0.0, 1.0);
    int hits = 0, skipped = 0;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 o{u(rng), u(rng), u(rng)};
        dvec3 d = randomUnit(rng) * (0.25 + 2.0 * u01(rng));  // not unit
        if (i % 7 == 0) d[i % 3] = 0;                         // axis-parallel slabs
        if (i % 29 == 0) d = dvec3(0, 0, 0), d[i % 3] = -1;
        const double tMin = i % 2 ? 0.0 : 0.3 * u01(rng);
        const double tMax = i % 5 == 0 ? kInf : tMin + 3.0 * u01(rng);
        TriangleId skip;
        if (i % 4 == 1) skip = ids[static_cast<size_t>(u01(rng) * double(ids.size())) % ids.size()];
        ExactTracer::Hit want = bruteClosest(s, o, d, tMin, tMax, skip);
        if (i % 4 == 3 && want.found) {  // skip the first hit: the next one must come out
            skip = want.id, ++skipped;
            want = bruteClosest(s, o, d, tMin, tMax, skip);
        }
        const ExactTracer::Hit got = tracer.closestHit(o, d, tMin, tMax, skip);
        ASSERT_EQ(got.found, want.found) << "ray " << i;
        EXPECT_EQ(tracer.occluded(o, d, tMin, tMax, skip), want.found) << "ray " << i;
        if (!want.found) continue;
        ++hits;
        EXPECT_EQ(got.t, want.t) << "ray " << i;
        EXPECT_EQ(got.id, want.id) << "ray " << i;
        EXPECT_EQ(got.b1, want.b1) << "ray " << i;
        EXPECT_EQ(got.b2, want.b2) << "ray " << i;
    }
    EXPECT_GT(hits, 4000);
    EXPECT_GT(skipped, 500);
}

TEST(ExactTracer, TiesGoToTheSmallerId) {
    // Rays through the vertices and edges of a planar grid meet several triangles at the same t
    // (t comes from the plane z = 0, so exactly); the smaller (mesh, prim) must win whatever the
    // BVH's order.
    Scene s;
    const int n = 24;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const dvec3 a(i, j, 0), b(i + 1, j, 0), c(i, j + 1, 0), d(i + 1, j + 1, 0);
            const size_t mesh = static_cast<size_t>((i * 7 + j * 3) % 4);
            s.addTriangle(mesh, a, b, d);
            s.addTriangle(mesh, a, d, c);
        }
    const ExactTracer tracer(s.views());
    std::mt19937_64 rng(3);
    std::uniform_int_distribution<int> cell(1, n - 1), half(0, 1);
    int ties = 0;
    for (int i = 0; i < 5000; ++i) {
        const dvec3 target(cell(rng) + 0.5 * half(rng), cell(rng), 0);
        const dvec3 o = target + dvec3(0, 0, 3) + 2.0 * randomUnit(rng) * dvec3(1, 1, 0);
        const dvec3 d = target - o;
        const ExactTracer::Hit want = bruteClosest(s, o, d, 0, 2, {});
        const ExactTracer::Hit got = tracer.closestHit(o, d, 0, 2);
        ASSERT_TRUE(want.found) << i;
        EXPECT_EQ(got.t, want.t) << i;
        ASSERT_EQ(got.id, want.id) << i;
        int atT = 0;
        s.forEach([&](TriangleId, const dvec3& a, const dvec3& b, const dvec3& c) {
            double t, b1, b2;
            atT += exact::rayTriangle(o, d, 0, 2, a, b, c, t, b1, b2) && t == want.t;
        });
        ties += atT > 1;
    }
    EXPECT_GT(ties, 1000);
}

// ---------------------------------------------------------------------------------------------
// 2 - 7. Closed forms

// The unit square at z = 0 as two triangles sharing the diagonal (0,0)-(1,1).
Scene unitSquare() {
    Scene s;
    s.addTriangle(0, {0, 0, 0}, {1, 0, 0}, {1, 1, 0});  // prim 0: below the diagonal (y < x)
    s.addTriangle(0, {0, 0, 0}, {1, 1, 0}, {0, 1, 0});  // prim 1: above it
    return s;
}

TEST(ExactTracer, SquareMarginIsDistanceToTheCrossedTrianglesBoundary) {
    const Scene s = unitSquare();
    const ExactTracer tracer(s.views());
    // Through (0.2, 0.7), in prim 1: its edges x = 0 (0.2), y = 1 (0.3), the diagonal (0.5 / sqrt
    // 2); prim 0 is 0.5 / sqrt 2 away. The ends are 1 away.
    ExactTracer::SegmentQuery q = tracer.segment({0.2, 0.7, 1}, {0, 0, -1}, 2.0, {}, 0.1, 0.0);
    EXPECT_TRUE(q.occluded);
    EXPECT_EQ(q.firstHitT, 1.0);
    EXPECT_EQ(q.firstHit, (TriangleId{0, 1}));
    EXPECT_NEAR(q.margin, 0.2, 1e-12);
    EXPECT_NEAR(q.marginT, 1.0, 1e-12);
    EXPECT_EQ(q.nearest, (TriangleId{0, 1}));
    EXPECT_FALSE(q.ambiguous);
    // The hit itself, from either side: prim 1 = (0,0), (1,1), (0,1), so (0.2, 0.7) has
    // barycentrics 0.2 (vertex 1) and 0.5 (vertex 2).
    for (const double z : {1.0, -1.0}) {
        const ExactTracer::Hit h = tracer.closestHit({0.2, 0.7, z}, {0, 0, -z}, 0, 2);
        ASSERT_TRUE(h.found);
        EXPECT_EQ(h.t, 1.0);
        EXPECT_EQ(h.id, (TriangleId{0, 1}));
        EXPECT_NEAR(h.b1, 0.2, 1e-15);
        EXPECT_NEAR(h.b2, 0.5, 1e-15);
    }
    // Through (0.3, 0.4): the square's outline is 0.3 away, but the crossed triangle's own
    // boundary includes the diagonal, 0.1 / sqrt 2 away.
    q = tracer.segment({0.3, 0.4, 1}, {0, 0, -1}, 2.0, {}, 0.05, 0.0);
    EXPECT_TRUE(q.occluded);
    EXPECT_EQ(q.firstHit, (TriangleId{0, 1}));
    EXPECT_NEAR(q.margin, 0.1 / std::sqrt(2.0), 1e-12);
    EXPECT_FALSE(q.ambiguous);
    EXPECT_TRUE(tracer.segment({0.3, 0.4, 1}, {0, 0, -1}, 2.0, {}, 0.08, 0.0).ambiguous);
}

TEST(ExactTracer, NearMissBesideAnEdge) {
    Scene s;
    s.addTriangle(0, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    const ExactTracer tracer(s.views());
    const dvec3 o{0.5, -1e-3, 1}, d{0, 0, -1};
    ExactTracer::SegmentQuery q = tracer.segment(o, d, 2.0, {}, 2e-3, 0.0);
    EXPECT_FALSE(q.occluded);
    EXPECT_NEAR(q.margin, 1e-3, 1e-12);
    EXPECT_NEAR(q.marginT, 1.0, 1e-12);
    EXPECT_EQ(q.nearest, (TriangleId{0, 0}));
    EXPECT_TRUE(q.ambiguous);
    q = tracer.segment(o, d, 2.0, {}, 5e-4, 0.0);
    EXPECT_FALSE(q.occluded);
    EXPECT_FALSE(q.ambiguous);
    EXPECT_FALSE(tracer.occluded(o, d, 0, 2));
    // The same segment moved onto the triangle, 1e-3 inside the edge: crossed, same margin.
    q = tracer.segment({0.5, 1e-3, 1}, d, 2.0, {}, 2e-3, 0.0);
    EXPECT_TRUE(q.occluded);
    EXPECT_NEAR(q.margin, 1e-3, 1e-12);
    EXPECT_TRUE(q.ambiguous);
}

TEST(ExactTracer, SegmentInThePlaneIsNotCrossingButAmbiguous) {
    Scene s;
    s.addTriangle(0, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    s.addTriangle(1, {6, 0, 0}, {5, 1, 0}, {5, 0, 1});  // the plane x + y + z = 6
    const ExactTracer tracer(s.views());
    // Over triangle 0, in its plane, exactly representable: margin exactly 0.
    ExactTracer::SegmentQuery q = tracer.segment({-1, 0.25, 0}, {1, 0, 0}, 4.0, {}, 1e-300, 0);
    EXPECT_FALSE(q.occluded);
    EXPECT_EQ(q.margin, 0.0);
    EXPECT_EQ(q.nearest, (TriangleId{0, 0}));
    EXPECT_TRUE(q.ambiguous);
    EXPECT_FALSE(tracer.occluded({-1, 0.25, 0}, {1, 0, 0}, 0, 4));
    // Over triangle 1, a slanted plane: margin within rounding of 0.
    const dvec3 p{5.2, 0.3, 0.5}, d{1, -1, 0};
    q = tracer.segment(p - 0.5 * d, d, 1.0, {}, 1e-12, 0);
    EXPECT_FALSE(q.occluded);
    EXPECT_LT(q.margin, 1e-15);
    EXPECT_TRUE(q.ambiguous);
    EXPECT_FALSE(tracer.closestHit(p - 0.5 * d, d, 0, 1).found);
}

TEST(ExactTracer, EndpointOnANeighbourAndSkip) {
    // A alone, skipped: a segment from its centroid at 45 degrees has nothing within reach.
    Scene s;
    s.addTriangle(0, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // A
    const TriangleId a{0, 0};
    const dvec3 centroid = dvec3(1, 1, 0) / 3.0, d = glm::normalize(dvec3(1, 0, 1));
    {
        const ExactTracer tracer(s.views());
        const ExactTracer::SegmentQuery q = tracer.segment(centroid, d, 10.0, a, 1e-6, 1e-6);
        EXPECT_FALSE(q.occluded);
        EXPECT_FALSE(q.ambiguous);
        EXPECT_EQ(q.margin, kInf);
        EXPECT_EQ(q.nearest, TriangleId{});
        // Not skipped, A is 0 away; the crossing is at t = 0 exactly (t comes from the plane),
        // outside (0, tMax).
        const ExactTracer::SegmentQuery q2 = tracer.segment(centroid, d, 10.0, {}, 1e-6, 1e-6);
        EXPECT_FALSE(q2.occluded);
        EXPECT_TRUE(q2.ambiguous);
        EXPECT_EQ(q2.margin, 0.0);
    }
    // B shares A's edge (1,0,0)-(0,1,0), folded down; the origin is on that edge.
    s.addTriangle(0, {1, 0, 0}, {0, 1, 0}, {1, 1, -0.5});  // B
    const ExactTracer tracer(s.views());
    const dvec3 o{0.5, 0.5, 0};
    ExactTracer::SegmentQuery q = tracer.segment(o, {0, 0, 1}, 10.0, a, 1e-9, 0.0);
    EXPECT_FALSE(q.occluded);
    EXPECT_EQ(q.margin, 0.0);
    EXPECT_EQ(q.marginT, 0.0);
    EXPECT_EQ(q.nearest, (TriangleId{0, 1}));
    EXPECT_TRUE(q.ambiguous);
    // Leaving downwards, through B's side: crossed at t = 0 only, which is not in (0, tMax).
    q = tracer.segment(o, {0, 0, -1}, 10.0, a, 1e-9, 0.0);
    EXPECT_FALSE(q.occluded);
    EXPECT_TRUE(q.ambiguous);
}

TEST(ExactTracer, InfiniteSegmentIsClippedToTheBounds) {
    Scene s;
    s.addTriangle(0, {-1, 5, 5}, {-1, 6, 5}, {-1, 5, 6});  // far off the ray
    s.addTriangle(1, {1000, -50, -50}, {1000, 100, -50}, {1000, -50, 100});
    const ExactTracer tracer(s.views());
    const dvec3 o{0, 0, 0}, d{1, 0, 0};
    const ExactTracer::SegmentQuery q = tracer.segment(o, d, kInf, {}, 1e-6, 1e-9);
    EXPECT_TRUE(q.occluded);
    EXPECT_EQ(q.firstHitT, 1000.0);
    EXPECT_EQ(q.firstHit, (TriangleId{1, 0}));
    // The margin is to the occluder's boundary (the hypotenuse, 50 / sqrt 2), not to the clipped
    // end, which lies ~1e-6 beyond the occluder.
    EXPECT_NEAR(q.margin, 50.0 / std::sqrt(2.0), 1e-9);
    EXPECT_EQ(q.nearest, (TriangleId{1, 0}));
    EXPECT_FALSE(q.ambiguous);
    EXPECT_TRUE(tracer.occluded(o, d, 0, kInf));
    EXPECT_EQ(tracer.closestHit(o, d, 0, kInf).t, 1000.0);
    // Away from everything: nothing.
    const ExactTracer::SegmentQuery away = tracer.segment(o, -d, kInf, {}, 1e-6, 1e-9);
    EXPECT_FALSE(away.occluded);
    EXPECT_FALSE(away.ambiguous);
    EXPECT_EQ(away.nearest, TriangleId{});
    // A near miss of the occluder's edge far along: found through the clip and tolPerT.
    const ExactTracer::SegmentQuery miss = tracer.segment({0, 0, -50.001}, d, kInf, {}, 0, 1e-5);
    EXPECT_FALSE(miss.occluded);
    EXPECT_NEAR(miss.margin, 1e-3, 1e-9);
    EXPECT_NEAR(miss.marginT, 1000.0, 1e-6);
    EXPECT_TRUE(miss.ambiguous);
    // A near miss past the bounds: descending slowly, the ray leaves the box through its floor
    // z = -50 at t ~ 999.9, then passes 1e-3 under the occluder's edge (x = 1000, z = -50) at
    // t = 1000. The clip must reach that far when tolPerT is in play.
    const dvec3 down = glm::normalize(dvec3(1, 0, -0.01)), m = -glm::normalize(dvec3(0.01, 0, 1));
    const dvec3 foot = dvec3(1000, 0, -50) + 1e-3 * m;
    const ExactTracer::SegmentQuery past =
        tracer.segment(foot - 1000.0 * down, down, kInf, {}, 0, 1e-5);
    EXPECT_FALSE(past.occluded);
    EXPECT_NEAR(past.margin, 1e-3, 1e-9);
    EXPECT_NEAR(past.marginT, 1000.0, 1e-6);
    EXPECT_TRUE(past.ambiguous);
}

TEST(ExactTracer, InfiniteSegmentAgreesWithClosestHit) {
    std::mt19937_64 rng(99);
    const Scene s = randomSoup(rng, 1000, 0.2);
    const ExactTracer tracer(s.views());
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    int hits = 0;
    for (int i = 0; i < 3000; ++i) {
        const dvec3 o{u(rng), u(rng), u(rng)}, d = randomUnit(rng);
        const ExactTracer::Hit h = tracer.closestHit(o, d, 0, kInf);
        const ExactTracer::SegmentQuery q = tracer.segment(o, d, kInf, {}, 1e-7, 1e-7);
        ASSERT_EQ(q.occluded, h.found) << i;
        if (!h.found) continue;
        ++hits;
        EXPECT_EQ(q.firstHitT, h.t) << i;
        EXPECT_EQ(q.firstHit, h.id) << i;
        EXPECT_TRUE(q.nearest != TriangleId{}) << i;
    }
    EXPECT_GT(hits, 300);
}

TEST(ExactTracer, TolerancePerUnitT) {
    // Along +x; at t = 10 an edge passes 1e-3 to the side.
    Scene s;
    s.addTriangle(0, {10, 1e-3, -1}, {10, 1e-3, 1}, {10, 1, 0});
    const ExactTracer tracer(s.views());
    ExactTracer::SegmentQuery q = tracer.segment({0, 0, 0}, {1, 0, 0}, 30.0, {}, 0.0, 2e-4);
    EXPECT_FALSE(q.occluded);
    EXPECT_NEAR(q.margin, 1e-3, 1e-12);
    EXPECT_NEAR(q.marginT, 10.0, 1e-9);
    EXPECT_TRUE(q.ambiguous);  // 1e-3 < 2e-4 * 10
    q = tracer.segment({0, 0, 0}, {1, 0, 0}, 30.0, {}, 0.0, 5e-5);
    EXPECT_NEAR(q.margin, 1e-3, 1e-12);  // within reach (5e-5 * 30), yet
    EXPECT_FALSE(q.ambiguous);           // 1e-3 > 5e-5 * 10
}

TEST(ExactTracer, DegenerateTrianglesAreNeverHitButCount) {
    Scene s;
    s.addTriangle(0, {-1, 0, 0}, {1, 0, 0}, {0, 0, 0});  // a zero-area sliver along x
    s.addTriangle(0, {0, 2, 0}, {0, 2, 0}, {0, 2, 0});   // a point
    const ExactTracer tracer(s.views());
    EXPECT_FALSE(tracer.occluded({0.5, 0, 1}, {0, 0, -1}, 0, 2));
    EXPECT_FALSE(tracer.closestHit({0, 2, 1}, {0, 0, -1}, 0, 2).found);
    ExactTracer::SegmentQuery q = tracer.segment({0.5, 0, 1}, {0, 0, -1}, 2.0, {}, 1e-9, 0);
    EXPECT_FALSE(q.occluded);
    EXPECT_EQ(q.margin, 0.0);
    EXPECT_TRUE(q.ambiguous);
    q = tracer.segment({0, 2.5, 1}, {0, 0, -1}, 2.0, {}, 1.0, 0);
    EXPECT_NEAR(q.margin, 0.5, 1e-15);
    EXPECT_EQ(q.nearest, (TriangleId{0, 1}));
}

TEST(ExactTracer, RejectsBadIndices) {
    const std::vector<dvec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<uint32_t> outOfRange{0, 1, 3}, notTriples{0, 1};
    EXPECT_THROW(ExactTracer({{&p, &outOfRange}}), std::invalid_argument);
    EXPECT_THROW(ExactTracer({{&p, &notTriples}}), std::invalid_argument);
    const ExactTracer empty({});
    EXPECT_EQ(empty.triangleCount(), 0u);
    EXPECT_FALSE(empty.occluded({0, 0, 0}, {1, 0, 0}, 0, kInf));
    EXPECT_FALSE(empty.segment({0, 0, 0}, {1, 0, 0}, kInf, {}, 1, 1).ambiguous);
}

// ---------------------------------------------------------------------------------------------
// 8. segment() against brute force: the BVH's widened boxes must not lose a triangle in reach

void checkSegmentsAgainstBruteForce(uint64_t seed, int triangles, double size, int segments) {
    std::mt19937_64 rng(seed);
    const Scene s = randomSoup(rng, triangles, size);
    const ExactTracer tracer(s.views());
    struct Tri {
        TriangleId id;
        dvec3 a, b, c;
    };
    std::vector<Tri> tris;
    s.forEach([&](TriangleId id, const dvec3& a, const dvec3& b, const dvec3& c) {
        tris.push_back({id, a, b, c});
    });
    std::uniform_real_distribution<double> u(-1.2, 1.2), u01(0.0, 1.0);
    int ambiguous = 0, occluded = 0, clean = 0;
    for (int i = 0; i < segments; ++i) {
        dvec3 o{u(rng), u(rng), u(rng)};
        TriangleId skip;
        if (i % 2 == 0) {  // a shadow ray: from a point on a triangle, which is skipped
            const Tri& t = tris[static_cast<size_t>(u01(rng) * double(tris.size())) % tris.size()];
            const double r1 = u01(rng), r2 = u01(rng) * (1 - r1);
            o = t.a + r1 * (t.b - t.a) + r2 * (t.c - t.a);
            skip = t.id;
        }
        const dvec3 d = randomUnit(rng) * (i % 3 == 0 ? 1.0 : 0.5 + u01(rng));
        const double tMax = 0.05 + 2.5 * u01(rng);
        const double tolAbs = i % 5 == 0 ? 0.0 : std::pow(10.0, -1.0 - 5.0 * u01(rng));
        const double tolPerT = i % 4 == 0 ? 0.0 : std::pow(10.0, -1.0 - 5.0 * u01(rng));
        const auto want = bruteSegment(s, o, d, tMax, skip, tolAbs, tolPerT);
        const auto got = tracer.segment(o, d, tMax, skip, tolAbs, tolPerT);
        ASSERT_EQ(got.occluded, want.occluded) << "segment " << i;
        ASSERT_EQ(got.ambiguous, want.ambiguous) << "segment " << i;
        EXPECT_EQ(got.margin, want.margin) << "segment " << i;
        EXPECT_EQ(got.marginT, want.marginT) << "segment " << i;
        EXPECT_EQ(got.nearest, want.nearest) << "segment " << i;
        EXPECT_EQ(got.firstHitT, want.firstHitT) << "segment " << i;
        EXPECT_EQ(got.firstHit, want.firstHit) << "segment " << i;
        EXPECT_EQ(got.occluded, tracer.occluded(o, d, 0, tMax, skip)) << "segment " << i;
        ambiguous += want.ambiguous, occluded += want.occluded;
        clean += !want.ambiguous && want.nearest != TriangleId{};
    }
    // Every kind of answer shows up, so the comparison means something.
    EXPECT_GT(ambiguous, segments / 20);
    EXPECT_GT(occluded, segments / 10);
    EXPECT_GT(clean, segments / 20);
}

TEST(ExactTracer, SegmentMatchesBruteForceSparse) {
    checkSegmentsAgainstBruteForce(2024, 1500, 0.15, 2000);
}

TEST(ExactTracer, SegmentMatchesBruteForceDense) {
    checkSegmentsAgainstBruteForce(77, 2500, 0.05, 1000);
}

TEST(ExactTracer, ConcurrentQueriesMatchSerial) {
    std::mt19937_64 rng(31);
    const Scene s = randomSoup(rng, 1500, 0.15);
    const ExactTracer tracer(s.views());
    const int count = 4000;
    std::vector<dvec3> origins(count), dirs(count);
    std::uniform_real_distribution<double> u(-1.2, 1.2);
    for (int i = 0; i < count; ++i)
        origins[i] = {u(rng), u(rng), u(rng)}, dirs[i] = randomUnit(rng);
    const auto query = [&](int i) {
        return tracer.segment(origins[i], dirs[i], 1.5, {}, 1e-3, 1e-4);
    };
    std::vector<ExactTracer::SegmentQuery> serial(count), parallel(count);
    for (int i = 0; i < count; ++i) serial[i] = query(i);
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
        threads.emplace_back([&, k] {
            for (int i = k; i < count; i += 4) parallel[i] = query(i);
        });
    for (std::thread& t : threads) t.join();
    for (int i = 0; i < count; ++i) {
        ASSERT_EQ(parallel[i].margin, serial[i].margin) << i;
        ASSERT_EQ(parallel[i].nearest, serial[i].nearest) << i;
        ASSERT_EQ(parallel[i].firstHitT, serial[i].firstHitT) << i;
    }
}

// ---------------------------------------------------------------------------------------------
// Throughput on a 75k-triangle height field (reported, not asserted: builds differ).

TEST(ExactTracer, Throughput75k) {
    const int n = 194;  // 2 * 193^2 = 74,498 triangles
    Scene s;
    s.meshes.resize(1);
    auto& m = s.meshes[0];
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = i / double(n - 1), z = j / double(n - 1);
            m.positions.push_back({x, 0.1 * std::sin(17 * x) * std::cos(13 * z), z});
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n), d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const ExactTracer tracer(s.views());
    const double buildS = std::chrono::duration<double>(Clock::now() - t0).count();
    ASSERT_EQ(tracer.triangleCount(), 2u * 193 * 193);

    // Shadow rays from points just above the surface towards a light.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int rays = 200000, segs = 20000;
    std::vector<dvec3> origins(rays);
    for (dvec3& o : origins) o = {u(rng), 0.1001 * std::sin(17 * u(rng)), u(rng)};
    const dvec3 light{0.3, 0.5, -0.4};
    int occ = 0;
    const auto t1 = Clock::now();
    for (const dvec3& o : origins) occ += tracer.occluded(o, light - o, 0, 1);
    const double occS = std::chrono::duration<double>(Clock::now() - t1).count();
    int amb = 0;
    const auto t2 = Clock::now();
    for (int i = 0; i < segs; ++i) {
        const dvec3 d = glm::normalize(light - origins[size_t(i)]);
        amb += tracer
                   .segment(origins[size_t(i)], d, glm::length(light - origins[size_t(i)]), {},
                            1e-6, 1e-7)
                   .ambiguous;
    }
    const double segS = std::chrono::duration<double>(Clock::now() - t2).count();
    std::printf(
        "[ exact   ] 75k build %.3f s; occluded %.2f Mrays/s (%d/%d occluded); "
        "segment %.2f Mrays/s (%d ambiguous)\n",
        buildS, rays / occS * 1e-6, occ, rays, segs / segS * 1e-6, amb);
    EXPECT_GT(occ, 0);
    EXPECT_LT(occ, rays);
}

}  // namespace
}  // namespace so
