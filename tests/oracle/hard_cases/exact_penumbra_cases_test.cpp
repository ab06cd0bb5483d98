// The exact penumbra pass's hard cases (docs/hard-cases.md, "6. Exact penumbrae"): overlapping
// occluders, an occluder touching the light, a receiver in the light's plane, a triangle edge-on
// to the point, thousands of tiny triangles, a concave crease in contact with the receiver; each
// against an independent float64 estimate by exact shadow rays, or against what the geometry says
// exactly.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "exact_penumbra_util.h"
#include "lambert.h"
#include "oracle/polygon_visibility.h"

namespace so::test {
namespace {

using glm::dvec3;

const AxisRect kLight = kPenumbraLight;

// An independent float64 estimate: the light's irradiance-weighted visibility by the midpoint
// rule on a cells x cells grid of the light, each cell's point tested with the exact tracer's own
// ray test (no clipping, no Lambert). Its error is the cells' share along the shadow's edges.
double gridEstimate(const ExactTracer& t, const RectLightShape& light, const dvec3& p,
                    const dvec3& n, int cells) {
    double lit = 0.0, all = 0.0;
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
            const dvec3 y = light.corner + ((i + 0.5) / cells) * light.edgeU +
                            ((j + 0.5) / cells) * light.edgeV;
            const dvec3 d = y - p;
            const double r2 = glm::dot(d, d);
            const double g = std::max(0.0, glm::dot(n, d)) *
                             std::max(0.0, -glm::dot(light.emitNormal, d)) / (r2 * r2);
            if (g == 0.0) continue;
            all += g;
            if (!t.occluded(p, d, 0.0, 1.0)) lit += g;
        }
    return all > 0.0 ? lit / all : 0.0;
}

// Two occluders whose projections overlap (the union must not count the overlap twice), one of
// them touching the light's plane, and a receiver under both.
TEST(ExactPenumbra, OverlappingOccludersAndOneTouchingTheLight) {
    Occluders occ;
    occ.addRect({1.5, -1.0, 0.5, -1.0, 0.5});
    occ.addRect({2.5, -0.5, 1.0, -0.2, 0.9});
    occ.add({0.2, 4.0, -0.5}, {1.5, 4.0, -0.5}, {0.8, 2.0, 0.3});  // an edge on the light's plane
    const ExactTracer t = occ.tracer();
    const RectLightShape l = lightShape(kLight);
    int partial = 0;
    for (const dvec3& p : {dvec3(0.2, 0, 0.1), dvec3(-1.2, 0, 0.6), dvec3(1.1, 0, -0.9),
                           dvec3(2.0, 0.3, 1.3), dvec3(0.5, 1.0, 0.0)}) {
        const PolygonVisibility v = visibility(t, l, p);
        const double estimate = gridEstimate(t, l, p, {0, 1, 0}, 800);
        EXPECT_NEAR(v.V, estimate, 3e-3) << p.x << " " << p.z;
        partial += v.V > 0.0 && v.V < 1.0;
    }
    EXPECT_GE(partial, 3) << "the points should be in the penumbra";
}

// A receiver in the light's plane or behind it sees none of a one-sided light; a triangle whose
// plane holds the point casts nothing (its projection is a segment).
TEST(ExactPenumbra, ReceiverInTheLightsPlaneAndATriangleEdgeOnToThePoint) {
    Occluders occ;
    const dvec3 p(0.25, 0.0, 0.1);
    occ.add(p + dvec3(0.0, 1.0, -1.0), p + dvec3(0.0, 3.0, 1.0), p + dvec3(0.0, 2.5, -0.8));
    const ExactTracer t = occ.tracer();
    const RectLightShape l = lightShape(kLight);
    const PolygonVisibility edgeOn = visibility(t, l, p);
    EXPECT_EQ(edgeOn.status, PolygonVisibilityStatus::Exact);
    EXPECT_EQ(edgeOn.V, 1.0);
    EXPECT_EQ(edgeOn.occluders, 0u);
    // Moved off its plane, the same triangle does cast a shadow.
    EXPECT_LT(visibility(t, l, p + dvec3(0.05, 0.0, 0.0)).V, 0.999);
    for (const dvec3& q : {dvec3(0.0, 4.0, 0.0), dvec3(3.0, 4.0, 0.0), dvec3(0.0, 4.5, 0.0)}) {
        const PolygonVisibility v = visibility(t, l, q);
        EXPECT_EQ(v.status, PolygonVisibilityStatus::NoLight) << q.y;
        EXPECT_EQ(v.V, 0.0);
    }
}

// A sieve of thousands of tiny triangles (a checkerboard: half the cells): slivers and shared
// vertices everywhere, against the independent estimate.
TEST(ExactPenumbra, ThousandsOfTinyTriangles) {
    Occluders occ;
    const int cells = 60;
    const double size = 2.0 / cells;
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
            if ((i + j) % 2) continue;
            const double x = -1.0 + i * size, z = -1.0 + j * size;
            occ.add({x, 1.5, z}, {x + size, 1.5, z}, {x + size, 1.5, z + size});
            occ.add({x, 1.5, z}, {x + size, 1.5, z + size}, {x, 1.5, z + size});
        }
    ASSERT_EQ(occ.indices.size() / 3, size_t(cells * cells));
    const ExactTracer t = occ.tracer();
    const RectLightShape l = lightShape(kLight);
    // The pyramid to the light holds about 400, 200 and 40 of them at these points.
    for (const dvec3& p : {dvec3(0.1, 0, 0.1), dvec3(1.4, 0, 0.7), dvec3(0.1, 1.2, 0.05)}) {
        const PolygonVisibility v = visibility(t, l, p);
        ASSERT_EQ(v.status, PolygonVisibilityStatus::Exact);
        EXPECT_GT(v.occluders, p.y > 0.0 ? 20u : 100u);
        const double estimate = gridEstimate(t, l, p, {0, 1, 0}, 1000);
        EXPECT_NEAR(v.V, estimate, 3e-3) << p.x << " " << p.y;
    }
    // A cap on the work: past it the point has no exact answer (the pass keeps the sample).
    EXPECT_EQ(rectLightVisibility(t, l, {0.1, 0, 0.1}, {0, 1, 0}, {}, 50).status,
              PolygonVisibilityStatus::TooManyOccluders);
}

// A concave crease, the receiver in contact with its occluder: the receiver's plane (y = 0, x <= 0)
// meets a plane rising at slope 0.1 from the crease line x = 0 to x = 4, and a light stands low
// beyond it (x = 5, heights 0.1 to 1.1, facing -x). From p = (-d, e, 0), e above the receiver, a
// ray to the light's height h passes x = 4 at e + (h - e)(4 + d)/(5 + d), under the rising
// plane's 0.4 exactly when h < e + (0.4 - e)(5 + d)/(4 + d), for every z: V is Lambert's formula
// over the light above that height, over the whole light's. On the surface (e = 0) with the point
// up to 1e-10 from the crease, and lifted by the sampled pass's origin offset and more (the exact
// pass answers for the point it is given; docs/benchmarks.md, bench_exact_penumbra).
TEST(ExactPenumbra, ConcaveCreaseInContactWithTheReceiver) {
    Occluders occ;
    occ.add({-10, 0, -10}, {0, 0, -10}, {0, 0, 10});  // the receiver's plane, up to the crease
    occ.add({-10, 0, -10}, {0, 0, 10}, {-10, 0, 10});
    occ.add({0, 0, -10}, {4, 0.4, -10}, {4, 0.4, 10});  // the rising plane
    occ.add({0, 0, -10}, {4, 0.4, 10}, {0, 0, 10});
    const ExactTracer t = occ.tracer();
    // cross(edgeU, edgeV) = -x: it emits towards the crease.
    const RectLightShape l{{5, 0.1, -0.5}, {0, 0, 1}, {0, 1, 0}, {-1, 0, 0}};
    const dvec3 n(0, 1, 0);
    const auto part = [&](const dvec3& p, double y0, double y1) {
        return cosineWeightedSolidAngle(p, n,
                                        {{5, y0, -0.5}, {5, y0, 0.5}, {5, y1, 0.5}, {5, y1, -0.5}});
    };
    for (double d : {1e-1, 1e-4, 1e-7, 1e-10})
        for (double e : {0.0, 7.6e-6, 1e-3}) {
            const dvec3 p(-d, e, 0.0);
            const double hidden = e + (0.4 - e) * (5 + d) / (4 + d);
            const double closedForm = part(p, hidden, 1.1) / part(p, 0.1, 1.1);
            const PolygonVisibility v = visibility(t, l, p);
            ASSERT_EQ(v.status, PolygonVisibilityStatus::Exact) << d << " " << e;
            EXPECT_NEAR(v.V, closedForm, 1e-8) << "d " << d << ", e " << e;
            EXPECT_GT(v.V, 0.7);  // the hidden lower part weighs less: nearer p's horizon
            EXPECT_LT(v.V, 0.9);
        }
    // And against the independent estimate once, at the point nearest the crease.
    EXPECT_NEAR(visibility(t, l, {-1e-10, 0, 0}).V, gridEstimate(t, l, {-1e-10, 0, 0}, n, 800),
                3e-3);
}

}  // namespace
}  // namespace so::test
