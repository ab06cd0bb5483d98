// Disk and sphere lights in the exact pass (oracle/disk_bounds.h): the closed forms of the disk's
// and the sphere's unoccluded irradiance, the bound against a closed form and against a
// 16,384-sided answer, its width against the polygons' sides, and the pass in the oracle
// (against the sampled intervals on the shipped sphere scene, at any thread count).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bunny_scene.h"
#include "cli_run.h"
#include "core/channels.h"
#include "core/lights/make_light.h"
#include "core/scene.h"
#include "exact_penumbra_util.h"
#include "oracle/disk_bounds.h"
#include "oracle/exact_penumbra.h"
#include "oracle/oracle.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;
using glm::dvec3;

constexpr double kPi = std::numbers::pi;

// The receivers the closed-form tests use: points on and off the axis, normals tilted.
std::vector<std::pair<dvec3, dvec3>> receivers() {
    std::vector<std::pair<dvec3, dvec3>> out;
    for (const dvec3& p : {dvec3(0, 0, 0), dvec3(0.25, 0, 0.125), dvec3(3, 0.5, -2),
                           dvec3(-1, 3.5, 0.5), dvec3(0.9, 3.9, 0.1)})
        for (const dvec3& n : {dvec3(0, 1, 0), glm::normalize(dvec3(0.3, 1, -0.2)),
                               glm::normalize(dvec3(-0.5, 0.6, 0.4))})
            out.push_back({p, n});
    return out;
}

TEST(DiskBounds, ClosedFormLiesBetweenTheInscribedAndCircumscribedPolygons) {
    const DiskLightShape disk = downDisk();
    int checked = 0;
    for (const auto& [p, n] : receivers()) {
        if (!diskAboveHorizon(disk, p, n)) continue;
        const double closed = diskSolidAngle(disk, p, n);
        const double in =
            std::abs(cosineWeightedSolidAngle(p, n, inscribedPolygon(disk, 16384, 1)));
        const double out =
            std::abs(cosineWeightedSolidAngle(p, n, circumscribedPolygon(disk, 16384, 1)));
        EXPECT_LE(in, closed) << p.x << " " << p.y;
        EXPECT_GE(out, closed) << p.x << " " << p.y;
        // 16,384 sides: the polygons differ from the disk by (pi/n)^2 = 3.7e-8 of its area.
        EXPECT_NEAR(in, closed, 1e-7 * closed);
        ++checked;
    }
    EXPECT_GE(checked, 8);
}

// The form factor of a sphere: pi (R/d)^2 cos(theta), for a sphere wholly above the horizon.
TEST(DiskBounds, SphereSilhouetteGivesTheSphereClosedForm) {
    const dvec3 c(0.5, 4.0, -0.25);
    const double R = 0.6;
    int checked = 0;
    for (const auto& [p, n] : receivers()) {
        const dvec3 w = c - p;
        const double d = glm::length(w), cosTheta = glm::dot(n, w) / d;
        if (!(d * cosTheta > R)) continue;  // part of the sphere below the horizon
        const DiskLightShape s = sphereSilhouette(c, R, p);
        ASSERT_TRUE(diskAboveHorizon(s, p, n));
        const double expected = kPi * (R / d) * (R / d) * cosTheta;
        EXPECT_NEAR(diskSolidAngle(s, p, n), expected, 1e-13 * expected) << p.x << " " << p.y;
        // The silhouette circle lies on the sphere.
        EXPECT_NEAR(glm::length(s.center + s.radius * s.e1 - c), R, 1e-14);
        ++checked;
    }
    EXPECT_GE(checked, 8);
}

// A square occluder under the disk's centre (y = 3, 0.4 wide): from points under it the square's
// shadow lies inside the disk, V = 1 - Phi(shadow) / U(disk) in closed form, and the bound is
// that to rounding. From points about 2 units off the axis its shadow crosses the disk's edge:
// against 16,384 sides.
Occluders squareOccluder(const AxisRect& square) {
    Occluders occ;
    occ.addRect(square);
    return occ;
}
struct SquareUnderDisk {
    AxisRect square{3.0, 0.05, 0.45, -0.075, 0.325};
    Occluders occ = squareOccluder(square);
    ExactTracer tracer = occ.tracer();  // over occ's vectors: a SquareUnderDisk is never moved
};

// The square's shadow through p on the light's plane (y = 4), by central projection.
std::vector<dvec3> shadowOfSquare(const AxisRect& sq, const dvec3& p, double lightY) {
    std::vector<dvec3> out;
    for (const dvec3& q : {dvec3(sq.x0, sq.y, sq.z0), dvec3(sq.x1, sq.y, sq.z0),
                           dvec3(sq.x1, sq.y, sq.z1), dvec3(sq.x0, sq.y, sq.z1)})
        out.push_back(p + (q - p) * ((lightY - p.y) / (q.y - p.y)));
    return out;
}

TEST(DiskBounds, SquareShadowInsideTheDiskMatchesTheClosedForm) {
    const SquareUnderDisk s;
    const DiskLightShape disk = downDisk();
    const DiskBoundOptions options;
    double worst = 0.0;
    for (const dvec3& p : {dvec3(0.2, 0, 0.1), dvec3(0.8, 0.5, 0.6), dvec3(-0.3, 1.0, -0.2)}) {
        const dvec3 n(0, 1, 0);
        const double shadow =
            std::abs(cosineWeightedSolidAngle(p, n, shadowOfSquare(s.square, p, 4.0)));
        const double expected = 1.0 - shadow / diskSolidAngle(disk, p, n);
        const DiskVisibility v = diskLightVisibility(s.tracer, disk, p, n, {}, 1000, options);
        ASSERT_EQ(v.counts.status, PolygonVisibilityStatus::Exact);
        EXPECT_LE(v.lower, expected);
        EXPECT_GE(v.upper, expected);
        // The polygons' bound has no width where no shadow crosses the disk's edge: the stated
        // one is the shadows' quantisation allowance alone.
        const LightShadows shadows = diskShadows(s.tracer, disk, p, n, {}, 1000);
        const DiskBound b = diskBoundAt(shadows, disk, p, n, 32);
        EXPECT_LT(b.upper - b.lower, 1e-12);
        EXPECT_NEAR(v.halfWidth(), 1e-8, 1e-12);
        EXPECT_EQ(v.sides, options.minSides);
        worst = std::max(worst, std::fabs(v.counts.V - expected));
    }
    std::printf("[ disk ] square shadow inside the disk: max |V - closed form| = %.3g\n", worst);
    EXPECT_LT(worst, 5e-9);
}

// Points whose view of the disk the square's shadow crosses at its edge, on the floor and on
// tilted receivers whose horizon cuts the disk: the adaptive answer's interval reaches the target
// and holds the 16,384-sided one's.
TEST(DiskBounds, SquareShadowAcrossTheEdgeWithinTheTargetOfManySides) {
    const SquareUnderDisk s;
    const DiskLightShape disk = downDisk();
    const DiskBoundOptions options;
    size_t crossing = 0, clipped = 0;
    double worst = 0.0;
    for (const dvec3& n : {dvec3(0, 1, 0), glm::normalize(dvec3(0.9, 0.25, 0.1))})
        for (int i = 0; i <= 12; ++i)
            for (int j = 0; j <= 12; ++j) {
                const dvec3 p(-2.0 + 0.375 * i, 0.0, -2.0 + 0.375 * j);
                const DiskVisibility v =
                    diskLightVisibility(s.tracer, disk, p, n, {}, 1000, options);
                // Tilted receivers may see none of the disk.
                if (v.counts.status == PolygonVisibilityStatus::NoLight) continue;
                ASSERT_EQ(v.counts.status, PolygonVisibilityStatus::Exact);
                if (v.counts.occluders == 0) continue;
                const LightShadows shadows = diskShadows(s.tracer, disk, p, n, {}, 1000);
                const DiskBound fine = diskBoundAt(shadows, disk, p, n, kMaxDiskSides);
                EXPECT_LE(v.halfWidth(), options.targetHalfWidth);
                EXPECT_TRUE(v.reachedTarget);
                // The two intervals are both sure (the fine one up to the shadows' quantisation,
                // which the adaptive one's allowance holds): they overlap.
                EXPECT_LE(v.lower, fine.upper) << p.x << " " << p.z;
                EXPECT_GE(v.upper, fine.lower) << p.x << " " << p.z;
                worst = std::max(worst, std::fabs(v.counts.V - 0.5 * (fine.lower + fine.upper)));
                crossing += v.sides > options.minSides;
                clipped += !diskAboveHorizon(disk, p, n);
            }
    std::printf(
        "[ disk ] %zu points needed more than %u sides, %zu with the horizon cutting the "
        "disk; max |V - V(16,384 sides)| = %.3g\n",
        crossing, options.minSides, clipped, worst);
    EXPECT_GT(crossing, 20u);
    EXPECT_GT(clipped, 20u);
    EXPECT_LT(worst, 2.0 * options.targetHalfWidth);
}

// The interval's width falls as 1/n^2: doubling the sides divides it by about 4.
TEST(DiskBounds, HalfWidthFallsAsOneOverNSquared) {
    const SquareUnderDisk s;
    const DiskLightShape disk = downDisk();
    int measured = 0;
    for (const dvec3& p : {dvec3(-1.75, 0.0, 0.125), dvec3(2.0, 0.0, -1.25)}) {
        const dvec3 n(0, 1, 0);
        const LightShadows shadows = diskShadows(s.tracer, disk, p, n, {}, 1000);
        ASSERT_GT(shadows.counts().occluders, 0u);
        const DiskBound coarse = diskBoundAt(shadows, disk, p, n, 32);
        ASSERT_GT(coarse.upper - coarse.lower, 1e-6) << "the shadow crosses the disk's edge";
        ++measured;
        double previous = 0.0;
        for (uint32_t sides = 32; sides <= 4096; sides *= 2) {
            const DiskBound b = diskBoundAt(shadows, disk, p, n, sides);
            const double width = b.upper - b.lower;
            std::printf("[ disk ] (%g, %g): %5u sides, width %.3e, width n^2 %.4f\n", p.x, p.z,
                        sides, width, width * double(sides) * double(sides));
            if (previous > 0.0) {
                EXPECT_GT(previous / width, 3.5) << sides;
                EXPECT_LT(previous / width, 4.5) << sides;
            }
            previous = width;
        }
    }
    EXPECT_EQ(measured, 2);
}

// A sphere light as a scene: the shipped one, small.
Scene shippedSphereScene(int width, int height) {
    Scene scene = loadScene(std::string(SO_SCENES_DIR) + "/sphere_light.scene.json");
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

// The exact pass on the shipped sphere scene beside the sampled one (--penumbra both): its bounds
// reach the target, and V_exact lies in the sampled 95% intervals at about the nominal rate.
TEST(ExactDiskSphere, ShippedSphereSceneWithinTheSampledIntervals) {
    const Scene scene = shippedSphereScene(96, 72);
    OracleOptions o;
    o.area.fixedSpp = 1024;
    o.penumbra.method = PenumbraMethod::Both;
    const OracleResult r = runOracle(scene, o);
    const ExactPenumbraStats& st = *r.stats.lights[0].area->exact;
    EXPECT_EQ(st.errorKind, "bound");
    EXPECT_TRUE(st.notApplied.empty());
    const double n = double(st.pixelsExact), share = double(st.outsideInterval) / n;
    std::printf(
        "[ sphere ] %llu exact pixels, %.4f outside the sampled 95%% interval, mean "
        "|V_exact - V| %.2e, half-width max %.2e, sides max %llu, %llu missed the "
        "target; exact pass %.3f s, sampled %.3f s\n",
        (unsigned long long)st.pixelsExact, share, st.sumAbsDifference / n, st.boundHalfWidthMax,
        (unsigned long long)st.boundSidesMax, (unsigned long long)st.boundTargetMissed, st.seconds,
        r.stats.lights[0].area->seconds);
    ASSERT_GT(st.pixelsExact, 100u);
    EXPECT_LE(share, 0.05 + 3.0 * std::sqrt(0.05 * 0.95 / n));
    EXPECT_LE(st.boundHalfWidthMax, 1e-6);
    EXPECT_EQ(st.boundTargetMissed, 0u);
    const float* bound = r.image.channel("globe.bound");
    const float* exact = r.image.channel("globe.exact");
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (exact[i] != 1.0f) {
            EXPECT_EQ(bound[i], 0.0f) << i;
        }
    }
}

// A disk light in the closed-form scene's place, traced with --penumbra exact at 1 and 2
// threads: the same V and bound planes, bit for bit.
TEST(ExactDiskSphere, SameImageAtAnyThreadCount) {
    PenumbraScene s = makePenumbraScene(64, 48);
    Light& l = s.scene.lights[0];
    l = diskLight(l.name, l.wsPosition, {0, -1, 0}, 0.75);
    std::vector<std::vector<float>> images;
    for (int threads : {1, 2}) {
        OracleOptions o;
        o.threads = threads;
        o.penumbra.method = PenumbraMethod::Exact;
        o.penumbra.allPixels = true;
        const OracleResult r = runOracle(s.scene, o);
        std::vector<float> planes;
        for (const char* name : {"panel.V", "panel.bound", "panel.exact"}) {
            const float* v = r.image.channel(name);
            planes.insert(planes.end(), v, v + r.image.pixelCount());
        }
        images.push_back(planes);
        EXPECT_GT(r.stats.lights[0].area->exact->pixelsExact, 1000u);
    }
    EXPECT_EQ(images[0], images[1]);
}

// The bunny under a disk light low on its left (the rect of useLowRectLight as a disk of radius
// 1.5 facing +x): many pixels in umbra among hundreds of occluders, a closed mesh seen from
// outside.
Scene bunnyUnderDisk(const MeshPrimitive& bunny) {
    Scene scene = makeBunnyScene(bunny, 64, 48);
    useLowRectLight(scene);
    Light& l = scene.lights[0];
    l = diskLight(l.name, l.wsPosition, {1, 0, 0}, 1.5);
    finalizeScene(scene);
    return scene;
}

// The exact pass's shortcuts and back faces (occluder_union.h, mesh_facing.h) hold for the bound
// as for a polygon: they are about segments from the point, so they hold for every region inside
// the gathering polygon's pyramid, P_in and P_out among them. With both on and both off, on the
// bunny under a disk light and on the shipped sphere scene, every pixel's two intervals overlap
// (the true V lies in both: |V_on - V_off| <= bound_on + bound_off, plus the shadows'
// quantisation, which the back faces may round differently along the silhouette), and the
// shortcuts did answer pixels (lit, covered) and leave back faces out.
TEST(ExactDiskSphere, ShortcutsAndBackFacesKeepTheBound) {
    std::vector<Scene> scenes = {shippedSphereScene(64, 48)};
    std::string why;
    if (const MeshPrimitive* bunny = cgalBunny(why)) scenes.push_back(bunnyUnderDisk(*bunny));
    for (const Scene& scene : scenes) {
        const bool bunny = scene.lights[0].name == "panel";  // its umbra: covered pixels
        const std::string name = scene.lights[0].name;
        std::vector<std::vector<float>> V, bound;
        std::vector<ExactPenumbraStats> stats;
        for (bool on : {true, false}) {
            OracleOptions o;
            o.penumbra.method = PenumbraMethod::Exact;
            o.penumbra.shortcuts = o.penumbra.backFaces = on;
            const OracleResult r = runOracle(scene, o);
            stats.push_back(*r.stats.lights[0].area->exact);
            const float* v = r.image.channel(name + ".V");
            const float* b = r.image.channel(name + ".bound");
            V.emplace_back(v, v + r.image.pixelCount());
            bound.emplace_back(b, b + r.image.pixelCount());
        }
        EXPECT_EQ(stats[0].errorKind, "bound");
        EXPECT_GT(stats[0].pixelsLit, 100u) << name;
        if (bunny) {
            EXPECT_GT(stats[0].pixelsCovered, 0u);
        }
        EXPECT_GT(stats[0].backFacesTotal, 0u) << name;
        EXPECT_EQ(stats[1].pixelsLit + stats[1].pixelsCovered + stats[1].backFacesTotal, 0u);
        EXPECT_EQ(stats[0].pixelsExact, stats[1].pixelsExact) << name;
        double worst = 0.0;
        for (size_t i = 0; i < V[0].size(); ++i) {
            const double d = std::fabs(double(V[0][i]) - double(V[1][i]));
            EXPECT_LE(d, double(bound[0][i]) + double(bound[1][i]) + 1e-7)
                << name << " pixel " << i << ": " << V[0][i] << " against " << V[1][i];
            worst = std::max(worst, d);
        }
        std::printf(
            "[ bound ] %s: %llu lit, %llu covered by the shortcuts, %llu of %llu candidates left "
            "out as back faces; max |V_on - V_off| %.3g\n",
            name.c_str(), (unsigned long long)stats[0].pixelsLit,
            (unsigned long long)stats[0].pixelsCovered, (unsigned long long)stats[0].backFacesTotal,
            (unsigned long long)stats[0].candidatesTotal, worst);
    }
}

// --penumbra exact on a sphere light finds its own pixels, as for a rect light: every pixel the
// camera hit is exact (bounded) with stderr and spp 0, none keeps a sampled 0 or 1 because its
// samples agreed, and where --penumbra both computed the same pixel (after its sampled pass) the
// two agree bit for bit.
TEST(ExactDiskSphere, ExactFindsItsOwnPixels) {
    const Scene scene = shippedSphereScene(64, 48);
    OracleOptions exactOptions;
    exactOptions.penumbra.method = PenumbraMethod::Exact;
    const OracleResult e = runOracle(scene, exactOptions);
    OracleOptions bothOptions;
    bothOptions.area.fixedSpp = 64;
    bothOptions.penumbra.method = PenumbraMethod::Both;
    const OracleResult b = runOracle(scene, bothOptions);
    const ExactPenumbraStats& st = *e.stats.lights[0].area->exact;
    const float* mask = e.image.channel("globe.exact");
    const float* spp = e.image.channel("globe.spp");
    const float* stderr_ = e.image.channel("globe.stderr");
    const float* V = e.image.channel("globe.V");
    const float* bothMask = b.image.channel("globe.exact");
    const float* bothV = b.image.channel("globe.V_exact");
    const float* A = e.image.channel("A");
    size_t hit = 0, exact = 0, same = 0;
    for (size_t i = 0; i < e.image.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        ++hit;
        if (mask[i] != 1.0f) continue;
        ++exact;
        EXPECT_EQ(spp[i], 0.0f) << i;
        EXPECT_EQ(stderr_[i], 0.0f) << i;
        if (bothMask[i] == 1.0f) {
            EXPECT_EQ(V[i], bothV[i]) << i;
            ++same;
        }
    }
    EXPECT_EQ(st.pixelsTooManyOccluders + st.pixelsAlphaTested, 0u);
    EXPECT_EQ(exact, hit);
    EXPECT_EQ(st.pixelsExact, hit);
    EXPECT_GT(same, 100u);
    EXPECT_GT(exact, b.stats.lights[0].area->exact->pixelsExact);
    EXPECT_EQ(e.stats.lights[0].area->raysTraced, 0u);  // no pixel was left to sample
}

// The command line: the bound's flags, a bad value one line naming its flag, and the channel
// and oracle.json's error_kind on a sphere light.
TEST(ExactDiskSphere, CommandLineFlags) {
    const std::string scene = std::string(SO_SCENES_DIR) + "/sphere_light.scene.json";
    const std::string out = ::testing::TempDir() + "so_exact_sphere_cli";
    const RunResult bad = run("trace " + scene + " --out " + out + " --bound-max-sides 100");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_EQ(bad.stderrText,
              "command line: --bound-max-sides: 100 is not a power of two in [32, 16384]\n");
    const RunResult ok =
        run("trace " + scene + " --out " + out +
            " --width 48 --height 36 --quiet --penumbra exact --bound-target 1e-5");
    ASSERT_EQ(ok.exitCode, 0) << ok.stderrText;
    const ChannelImage img = readExr(out + "/oracle.exr");
    EXPECT_NE(img.channel("globe.bound"), nullptr);
    std::ifstream in(out + "/oracle.json");
    std::stringstream text;
    text << in.rdbuf();
    const std::string json = text.str();
    EXPECT_NE(json.find("\"error_kind\": \"bound\""), std::string::npos);
    EXPECT_NE(json.find("\"target_half_width\": 1e-05"), std::string::npos);
}

}  // namespace
}  // namespace so::test
