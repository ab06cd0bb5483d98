// The exact penumbra pass's hard cases (docs/hard-cases.md, "6. Exact penumbrae"): overlapping
// occluders, an occluder touching the light, a receiver in the light's plane, a triangle edge-on
// to the point, thousands of tiny triangles; each against an independent float64 estimate by
// exact shadow rays, or against what the geometry says exactly.
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

}  // namespace
}  // namespace so::test
