// Disk and sphere lights' exact pass (oracle/disk_exact.h): the unoccluded disk's contour against
// the closed form and against 16,384-sided polygons (horizon-cut disks included), V inside the
// polygons' interval (disk_bounds.h, the independent check) for random occluders under disk and
// sphere lights, a square's shadow inside the disk against its closed form, and a disk half
// covered by an edge through its centre (V = 1/2 by symmetry), and a sphere light through the
// oracle's pass at 1 and 2 threads.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/lights/make_light.h"
#include "core/scene.h"
#include "exact_penumbra_util.h"
#include "oracle/disk_bounds.h"
#include "oracle/disk_exact.h"
#include "oracle/exact_penumbra.h"
#include "oracle/oracle.h"
#include "oracle/small_polygon.h"

namespace so::test {
namespace {

using glm::dvec2;
using glm::dvec3;

// Points on and off the axis, some near the disk's plane, with normals from up to tilted far
// enough that the horizon cuts the disk.
std::vector<std::pair<dvec3, dvec3>> receivers() {
    std::vector<std::pair<dvec3, dvec3>> out;
    for (const dvec3& p : {dvec3(0, 0, 0), dvec3(0.25, 0, 0.125), dvec3(3, 0.5, -2),
                           dvec3(-1, 3.5, 0.5), dvec3(0.9, 3.9, 0.1), dvec3(0.3, 3.95, 0.2)})
        for (const dvec3& n :
             {dvec3(0, 1, 0), glm::normalize(dvec3(0.3, 1, -0.2)),
              glm::normalize(dvec3(-0.5, 0.6, 0.4)), glm::normalize(dvec3(1, 0.05, 0.3)),
              glm::normalize(dvec3(-0.2, 0.1, -1))})
            out.push_back({p, n});
    return out;
}

// Phi of an n-gon (n = 16,384) clipped to p's horizon.
double polygonAbove(const std::vector<dvec3>& poly, const dvec3& p, const dvec3& n) {
    const std::vector<dvec3> lit = clipToHalfSpace(poly, {-n, -glm::dot(n, p)});
    return lit.size() < 3 ? 0.0 : std::abs(cosineWeightedSolidAngle(p, n, lit));
}

// A square about the disk, in (u, v), cut by p's horizon: the region the contour integrates
// against where only the horizon's edge (or none) crosses the circle.
std::vector<dvec2> squareAbove(const DiskLightShape& d, const dvec3& p, const dvec3& n) {
    const double h = 1.5 * d.radius;
    std::vector<dvec3> square;
    for (const dvec2& c : {dvec2(-h, -h), dvec2(h, -h), dvec2(h, h), dvec2(-h, h)})
        square.push_back(d.center + c.x * d.e1 + c.y * d.e2);
    std::vector<dvec2> out;
    for (const dvec3& y : clipToHalfSpace(square, {-n, -glm::dot(n, p)}))
        out.push_back({glm::dot(y - d.center, d.e1), glm::dot(y - d.center, d.e2)});
    return out;
}

TEST(DiskExact, UnoccludedDiskMatchesClosedFormAndManySides) {
    const DiskLightShape disk = downDisk();
    int above = 0, cut = 0;
    double worstClosed = 0.0, worstContour = 0.0;
    for (const auto& [p, n] : receivers()) {
        const DiskArc arc = diskArcAbove(disk, p, n);
        if (!(arc.half > 0.0)) continue;
        const DiskIntegral whole = diskUnoccludedSolidAngle(disk, p, n);
        // The contour through the region's edges and the arcs: no closed form in it.
        const DiskIntegral contour = diskRegionSolidAngle(disk, p, n, {squareAbove(disk, p, n)});
        const double in = polygonAbove(inscribedPolygon(disk, kMaxDiskSides, 1.0, arc), p, n);
        const double out = polygonAbove(circumscribedPolygon(disk, kMaxDiskSides, 1.0, arc), p, n);
        ASSERT_GT(whole.value, 0.0);
        EXPECT_LE(in, whole.value + whole.error) << p.x << " " << p.y << " " << n.x;
        EXPECT_GE(out, whole.value - whole.error) << p.x << " " << p.y << " " << n.x;
        EXPECT_LE(in, contour.value + contour.error) << p.x << " " << p.y << " " << n.x;
        EXPECT_GE(out, contour.value - contour.error) << p.x << " " << p.y << " " << n.x;
        // The two ways agree to their stated errors, and those are tiny.
        EXPECT_LE(std::fabs(contour.value - whole.value), contour.error + whole.error)
            << p.x << " " << p.y << " " << n.x;
        EXPECT_LT(contour.error, 1e-10 * whole.value);
        worstContour = std::max(worstContour, std::fabs(contour.value / whole.value - 1.0));
        if (diskAboveHorizon(disk, p, n)) {
            EXPECT_EQ(whole.value, diskSolidAngle(disk, p, n));
            ++above;
        } else {
            ++cut;
        }
        worstClosed = std::max(worstClosed, (out - in) / whole.value);
    }
    std::printf(
        "[ disk exact ] %d wholly above, %d cut by the horizon; contour against the other "
        "way: max relative %.3g; 16,384-gons' relative width up to %.3g\n",
        above, cut, worstContour, worstClosed);
    EXPECT_GE(above, 10);
    EXPECT_GE(cut, 8);
}

// Random triangles between the floor and the light, seeded.
Occluders randomOccluders(uint32_t seed, const dvec3& lightCenter, double spread) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0), height(0.8, 3.2);
    Occluders occ;
    for (int k = 0; k < 12; ++k) {
        const dvec3 c(lightCenter.x + spread * u(rng), height(rng),
                      lightCenter.z + spread * u(rng));
        const double size = 0.15 + 0.35 * (0.5 + 0.5 * u(rng));
        occ.add(c + size * dvec3(u(rng), 0.3 * u(rng), u(rng)),
                c + size * dvec3(u(rng), 0.3 * u(rng), u(rng)),
                c + size * dvec3(u(rng), 0.3 * u(rng), u(rng)));
    }
    return occ;
}

struct IntervalCheck {
    int points = 0, partial = 0, cut = 0, cutPartial = 0;
    double worstOutside = 0.0, worstError = 0.0, sumError = 0.0;
};

// V +- error at p against the polygons' interval at `sides` (plus their quantisation allowance):
// both are sure, so they overlap.
void checkAgainstPolygons(const ExactTracer& tracer, const DiskLightShape& disk, const dvec3& p,
                          const dvec3& n, uint32_t sides, IntervalCheck& c) {
    if (!(diskArcAbove(disk, p, n).half > 0.0)) return;  // none of it above the horizon
    // A NoLight answer (V = 0) is checked as well: the polygons must find (next to) no light.
    const DiskExactVisibility v = diskLightExact(tracer, disk, p, n, {}, 100000);
    ASSERT_NE(v.counts.status, PolygonVisibilityStatus::TooManyOccluders);
    const LightShadows shadows = diskShadows(tracer, disk, p, n, {}, 100000);
    double lower = 1.0, upper = 1.0;
    if (shadows.status() == PolygonVisibilityStatus::NoLight) {
        lower = upper = 0.0;
    } else if (shadows.counts().shortcut == VisibilityShortcut::Covered) {
        lower = upper = 0.0;
    } else if (shadows.counts().occluders > 0) {
        const DiskBound b = diskBoundAt(shadows, disk, p, n, sides);
        lower = b.lower, upper = b.upper;
    }
    lower -= 1e-8, upper += 1e-8;
    const double V = v.counts.V;
    const double outside = std::max({0.0, lower - (V + v.error), (V - v.error) - upper});
    EXPECT_EQ(outside, 0.0) << p.x << " " << p.z << ": V " << V << " +- " << v.error << " against ["
                            << lower << ", " << upper << "]";
    // The stated error is the bound at most, and the polygons' interval is narrow
    // enough at these sides that V must be its midpoint to about its width.
    EXPECT_LE(v.error, 1e-5);
    EXPECT_LE(std::fabs(V - 0.5 * (lower + upper)), 0.5 * (upper - lower) + v.error);
    c.worstOutside = std::max(c.worstOutside, outside);
    c.worstError = std::max(c.worstError, v.error);
    c.sumError += v.error;
    ++c.points;
    const bool partial = V > 1e-6 && V < 1.0 - 1e-6, cut = !diskAboveHorizon(disk, p, n);
    c.partial += partial;
    c.cut += cut;
    c.cutPartial += cut && partial;
}

TEST(DiskExact, RandomOccludersInsideTheManySidedInterval) {
    const DiskLightShape disk = downDisk();
    IntervalCheck c;
    std::mt19937_64 rng(20261128);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (uint32_t seed = 1; seed <= 6; ++seed) {
        const Occluders occ = randomOccluders(seed, disk.center, 1.2);
        const ExactTracer tracer = occ.tracer();
        for (int k = 0; k < 20; ++k) {
            const dvec3 p(disk.center.x + 2.5 * u(rng), 0.0, disk.center.z + 2.5 * u(rng));
            const dvec3 n = k % 3 == 0 ? glm::normalize(dvec3(u(rng), 0.15, u(rng)))
                                       : glm::normalize(dvec3(0.3 * u(rng), 1.0, 0.3 * u(rng)));
            checkAgainstPolygons(tracer, disk, p, n, 4096, c);
        }
    }
    std::printf(
        "[ disk exact ] %d points (%d partly lit, %d horizon-cut, %d both): stated error mean "
        "%.3g, max %.3g; outside the 4,096-gons' interval by at most %.3g\n",
        c.points, c.partial, c.cut, c.cutPartial, c.sumError / std::max(1, c.points), c.worstError,
        c.worstOutside);
    EXPECT_GE(c.points, 100);
    EXPECT_GE(c.partial, 40);
    EXPECT_GE(c.cut, 5);
    EXPECT_GE(c.cutPartial, 5);
}

TEST(DiskExact, SphereLightRandomOccludersInsideTheManySidedInterval) {
    const dvec3 center(0.25, 4.2, 0.125);
    const double radius = 0.7;
    IntervalCheck c;
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (uint32_t seed = 11; seed <= 16; ++seed) {
        const Occluders occ = randomOccluders(seed, center, 1.2);
        const ExactTracer tracer = occ.tracer();
        for (int k = 0; k < 20; ++k) {
            const dvec3 p(center.x + 2.5 * u(rng), 0.0, center.z + 2.5 * u(rng));
            const dvec3 n = k % 3 == 0 ? glm::normalize(dvec3(u(rng), 0.15, u(rng)))
                                       : glm::normalize(dvec3(0.3 * u(rng), 1.0, 0.3 * u(rng)));
            checkAgainstPolygons(tracer, sphereSilhouette(center, radius, p), p, n, 4096, c);
        }
    }
    std::printf(
        "[ sphere exact ] %d points (%d partly lit, %d horizon-cut, %d both): stated error mean "
        "%.3g, max %.3g; outside the 4,096-gons' interval by at most %.3g\n",
        c.points, c.partial, c.cut, c.cutPartial, c.sumError / std::max(1, c.points), c.worstError,
        c.worstOutside);
    EXPECT_GE(c.points, 100);
    EXPECT_GE(c.partial, 40);
    EXPECT_GE(c.cutPartial, 3);
}

// A square under the disk (y = 3): from points under it its shadow lies inside the disk, and
// V = 1 - Phi(shadow) / Phi(disk) in closed form.
TEST(DiskExact, SquareShadowInsideTheDiskMatchesTheClosedForm) {
    const AxisRect sq{3.0, 0.05, 0.45, -0.075, 0.325};
    Occluders occ;
    occ.addRect(sq);
    const ExactTracer tracer = occ.tracer();
    const DiskLightShape disk = downDisk();
    double worst = 0.0;
    for (const dvec3& p : {dvec3(0.2, 0, 0.1), dvec3(0.8, 0.5, 0.6), dvec3(-0.3, 1.0, -0.2)}) {
        const dvec3 n(0, 1, 0);
        std::vector<dvec3> shadow;
        for (const dvec3& q : {dvec3(sq.x0, sq.y, sq.z0), dvec3(sq.x1, sq.y, sq.z0),
                               dvec3(sq.x1, sq.y, sq.z1), dvec3(sq.x0, sq.y, sq.z1)})
            shadow.push_back(p + (q - p) * ((4.0 - p.y) / (q.y - p.y)));
        const double expected =
            1.0 - std::abs(cosineWeightedSolidAngle(p, n, shadow)) / diskSolidAngle(disk, p, n);
        const DiskExactVisibility v = diskLightExact(tracer, disk, p, n, {}, 1000);
        ASSERT_EQ(v.counts.status, PolygonVisibilityStatus::Exact);
        EXPECT_LE(std::fabs(v.counts.V - expected), v.error);
        // The quantisation allowance and little else.
        EXPECT_LT(v.error, 1.01e-8);
        worst = std::max(worst, std::fabs(v.counts.V - expected));
    }
    std::printf("[ disk exact ] square shadow inside the disk: max |V - closed form| = %.3g\n",
                worst);
    EXPECT_LT(worst, 5e-9);
}

// An occluder whose edge, seen from a point on the axis, runs through the disk's centre: half
// the disk is hidden and V = 1/2 by symmetry, on a horizontal and on a tilted receiver (whose
// horizon cuts neither half more: tilted along the edge).
TEST(DiskExact, EdgeThroughTheCentreHidesHalf) {
    DiskLightShape disk;
    disk.center = {0.0, 4.0, 0.0};
    disk.radius = 1.0;
    disk.emitNormal = {0, -1, 0};
    diskAxes(disk.emitNormal, disk.e1, disk.e2);
    Occluders occ;
    occ.addRect({2.0, -5.0, 0.0, -5.0, 5.0});  // x < 0 at height 2
    const ExactTracer tracer = occ.tracer();
    const dvec3 p(0.0, 0.0, 0.0);
    for (const dvec3& n : {dvec3(0, 1, 0), glm::normalize(dvec3(0.0, 0.2, 1.0))}) {
        const DiskExactVisibility v = diskLightExact(tracer, disk, p, n, {}, 1000);
        ASSERT_EQ(v.counts.status, PolygonVisibilityStatus::Exact);
        EXPECT_GT(v.counts.occluders, 0u);
        EXPECT_LE(std::fabs(v.counts.V - 0.5), v.error) << n.z;
        EXPECT_NEAR(v.counts.V, 0.5, 1e-9) << n.z;
        std::printf("[ disk exact ] half covered (n.z %.2f): V - 1/2 = %.3g, stated error %.3g\n",
                    n.z, v.counts.V - 0.5, v.error);
    }
}

// The pass in the oracle (exact_penumbra.cpp) with a sphere light in the closed-form scene's
// place, at 1 and 2 threads: the same V, bound and exact planes, bit for bit (nothing is shared
// between points). The disk's is ExactDiskSphere.SameImageAtAnyThreadCount.
TEST(DiskExact, SphereSameImageAtAnyThreadCount) {
    PenumbraScene s = makePenumbraScene(64, 48);
    Light& l = s.scene.lights[0];
    l = sphereLight(l.name, l.wsPosition, 0.75);
    finalizeScene(s.scene);
    std::vector<std::vector<float>> images;
    for (int threads : {1, 2}) {
        OracleOptions o;
        o.threads = threads;
        o.penumbra.method = PenumbraMethod::Exact;
        const OracleResult r = runOracle(s.scene, o);
        std::vector<float> planes;
        for (const char* name : {"panel.V", "panel.bound", "panel.exact"}) {
            const float* v = r.image.channel(name);
            planes.insert(planes.end(), v, v + r.image.pixelCount());
        }
        images.push_back(planes);
        const ExactPenumbraStats& e = *r.stats.lights[0].area->exact;
        EXPECT_GT(e.pixelsExact, 1000u);
        EXPECT_GT(e.boundSidesTotal, 0u);  // contours were integrated
        EXPECT_LE(e.boundHalfWidthMax, 1e-7);
        EXPECT_EQ(e.boundTargetMissed, 0u);
    }
    EXPECT_EQ(images[0], images[1]);
}

}  // namespace
}  // namespace so::test
