// The exact penumbra pass (oracle/polygon_visibility.h, oracle/exact_penumbra.h) against the
// closed form of tests/support/lambert.h, against the sampled pass's own intervals and independent
// float64 estimates on a real mesh, at any thread count and through the command line. Its hard
// cases are in tests/oracle/hard_cases/exact_penumbra_cases_test.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bunny_scene.h"
#include "cli_run.h"
#include "core/channels.h"
#include "exact_penumbra_util.h"
#include "lambert.h"
#include "oracle/exact_penumbra.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/mesh_facing.h"
#include "oracle/oracle.h"
#include "oracle/penumbra_choice.h"
#include "oracle/polygon_visibility.h"
#include "oracle/reference_light.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;
using glm::dvec3;

// The closed-form scene's occluder: a 2 x 2 square at height 1.5, parallel to the light.
const AxisRect kOccluder = PenumbraScene{}.occluder;
const AxisRect kLight = kPenumbraLight;

TEST(ExactPenumbra, LambertMatchesTheClosedFormOfAnUnoccludedLight) {
    const RectLightShape l = lightShape(kLight);
    const std::vector<dvec3> rect = {l.corner, l.corner + l.edgeU, l.corner + l.edgeU + l.edgeV,
                                     l.corner + l.edgeV};
    for (const dvec3& p : {dvec3(0.3, 0.0, 0.2), dvec3(-3.0, 0.5, 2.0), dvec3(5.0, 3.9, 0.0)}) {
        const double phi = std::abs(cosineWeightedSolidAngle(p, {0, 1, 0}, rect));
        const double reference = polygonIrradiance(p, {0, 1, 0}, rect, l.emitNormal);
        EXPECT_NEAR(phi, reference, 1e-12 * reference) << p.x;
        // The other winding gives the opposite sign.
        std::vector<dvec3> reversed(rect.rbegin(), rect.rend());
        EXPECT_NEAR(cosineWeightedSolidAngle(p, {0, 1, 0}, reversed),
                    -cosineWeightedSolidAngle(p, {0, 1, 0}, rect), 1e-15);
    }
}

// Issue 31's bar: below 1e-6 of the closed form over every penumbra point, here on a dense grid of
// the floor and on tilted receivers whose horizon cuts the light.
TEST(ExactPenumbra, ClosedFormSquareOccluderWithinOneMillionth) {
    Occluders occ;
    occ.addRect(kOccluder);
    const ExactTracer t = occ.tracer();
    const RectLightShape l = lightShape(kLight);
    double worst = 0.0;
    size_t penumbra = 0, umbra = 0;
    for (const dvec3& n : {dvec3(0, 1, 0), glm::normalize(dvec3(0.9, 0.3, 0.1))}) {
        for (int i = 0; i <= 200; ++i)
            for (int j = 0; j <= 200; ++j) {
                const dvec3 p(-4.0 + 0.04 * i, 0.0, -4.0 + 0.04 * j);
                const double reference = exactRectLightRectOccluderV(p, n, kLight, kOccluder);
                const PolygonVisibility v = visibility(t, l, p, n);
                // The tilted receivers' horizon leaves some points no light at all.
                ASSERT_EQ(v.status, reference == 0.0 && v.V == 0.0 && v.occluders == 0
                                        ? v.status
                                        : PolygonVisibilityStatus::Exact);
                worst = std::max(worst, std::fabs(v.V - reference));
                penumbra += reference > 1e-9 && reference < 1.0 - 1e-9;
                umbra += reference == 0.0;
                if (reference == 0.0) {
                    EXPECT_EQ(v.V, 0.0) << "umbra is exactly 0";
                }
            }
    }
    std::printf("[ exact ] %zu penumbra and %zu umbra points: max |V - closed form| = %.3g\n",
                penumbra, umbra, worst);
    EXPECT_GT(penumbra, 5000u);
    EXPECT_GT(umbra, 1000u);
    EXPECT_LT(worst, 1e-6);
}

// The oracle with --penumbra exact on the closed-form scene (issue 45's hidden scene: a square
// occluder over a floor under a rect light, 200 x 200): the pass finds its own pixels, so every
// pixel the camera hit is exact, stderr 0 and spp 0 there, within float rounding of the closed
// form at its point; no pixel keeps a sampled 0 or 1 whose samples merely agreed (before issue
// 45 the fringe kept them, 0.0136 off at worst). No sampled pass runs.
TEST(ExactPenumbra, OracleExactEveryPixelMatchesTheClosedForm) {
    const PenumbraScene s = makePenumbraScene(200, 200);
    OracleOptions o;
    o.penumbra.method = PenumbraMethod::Exact;
    const OracleResult r = runOracle(s.scene, o);
    const ChannelImage& img = r.image;
    const float* V = img.channel("panel.V");
    const float* SE = img.channel("panel.stderr");
    const float* spp = img.channel("panel.spp");
    const float* exact = img.channel("panel.exact");
    ASSERT_NE(exact, nullptr);
    size_t hit = 0, penumbra = 0;
    double worst = 0.0;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (img.channel(ch::kHit)[i] == 0.0f) continue;
        ++hit;
        const dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]);
        const dvec3 n(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i], img.channel(ch::kNZ)[i]);
        const double reference = exactRectLightRectOccluderV(p, n, s.light, s.occluder);
        penumbra += reference > 0.0 && reference < 1.0;
        EXPECT_EQ(exact[i], 1.0f) << i;
        EXPECT_EQ(SE[i], 0.0f) << i;
        EXPECT_EQ(spp[i], 0.0f) << i;
        worst = std::max(worst, std::fabs(double(V[i]) - reference));
    }
    const AreaShadowStats& area = *r.stats.lights[0].area;
    const ExactPenumbraStats& st = *area.exact;
    EXPECT_EQ(st.pixelsExact, hit);
    EXPECT_EQ(area.pixelsSampled, 0u);
    EXPECT_EQ(area.raysTraced, 0u);
    EXPECT_GT(penumbra, 5000u);
    EXPECT_GT(st.pixelsLit, 1000u);
    EXPECT_GT(st.pixelsCovered, 100u);
    // P is stored in float: the closed form at the rounded point differs by about the
    // penumbra's gradient times 2^-24 of the coordinates, plus V's own float rounding.
    std::printf(
        "[ exact ] %zu pixels (%zu in the penumbra), %llu lit and %llu covered found "
        "without a union: max |V - closed form at the stored P| = %.3g\n",
        hit, penumbra, (unsigned long long)st.pixelsLit, (unsigned long long)st.pixelsCovered,
        worst);
    EXPECT_LT(worst, 1e-6);
}

// The shortcuts (occluder_union.h: lit without a union when no triangle cuts the pyramid, dark as
// soon as the shadows cover the light) give what computing the pixel gives, over every pixel of
// the closed-form scene and of the bunny (whose umbra pixels stop early among hundreds of
// occluders). Covered pixels are 0 either way; a lit pixel's computed V is Lambert's sum over
// Clipper's copy of the same polygon, equal to 1 within rounding.
TEST(ExactPenumbra, ShortcutsNeverDisagreeWithComputingThePixel) {
    std::vector<Scene> scenes = {makePenumbraScene(96, 72).scene};
    std::string why;
    if (const MeshPrimitive* bunny = cgalBunny(why)) {
        scenes.push_back(makeBunnyScene(*bunny, 64, 48));
        useLowRectLight(scenes.back());
    }
    for (const Scene& scene : scenes) {
        std::vector<std::vector<float>> planes;
        uint64_t lit = 0, covered = 0;
        for (bool shortcuts : {true, false}) {
            OracleOptions o;
            o.penumbra.method = PenumbraMethod::Exact;
            o.penumbra.shortcuts = shortcuts;
            const OracleResult r = runOracle(scene, o);
            const ExactPenumbraStats& st = *r.stats.lights[0].area->exact;
            if (shortcuts) lit = st.pixelsLit, covered = st.pixelsCovered;
            if (!shortcuts) {
                EXPECT_EQ(st.pixelsLit + st.pixelsCovered, 0u);
            }
            const float* v = r.image.channel(scene.lights[0].name + ".V");
            planes.emplace_back(v, v + r.image.pixelCount());
        }
        EXPECT_GT(lit, 1000u);
        EXPECT_GT(covered, 0u);
        size_t differing = 0;
        for (size_t i = 0; i < planes[0].size(); ++i) {
            EXPECT_NEAR(planes[0][i], planes[1][i], 1e-12) << i;
            differing += planes[0][i] != planes[1][i];
        }
        std::printf(
            "[ exact ] %zu pixels: %llu lit and %llu covered by the shortcuts; %zu pixels' "
            "float V differ from computing them\n",
            planes[0].size(), (unsigned long long)lit, (unsigned long long)covered, differing);
    }
}

// A unit cube's 12 triangles wound outwards (or inwards), optionally without its top.
void addCube(std::vector<dvec3>& P, std::vector<uint32_t>& I, bool inwards, bool open) {
    P.clear();
    I.clear();
    for (int k = 0; k < 8; ++k) P.push_back(dvec3(k & 1, (k >> 1) & 1, (k >> 2) & 1));
    // Faces as quads, counter-clockwise seen from outside.
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int f = 0; f < 6; ++f) {
        if (open && f == 3) continue;  // y = 1
        const uint32_t* q = quads[f];
        for (const auto& t : {std::array{q[0], q[1], q[2]}, std::array{q[0], q[2], q[3]}})
            inwards ? I.insert(I.end(), {t[0], t[2], t[1]}) : I.insert(I.end(), {t[0], t[1], t[2]});
    }
}

// Which triangles of a closed part may be left out: from outside a cube wound outwards only the
// faces the point is in front of count (+1), from inside those it is behind (-1), and the other
// way round for a cube wound inwards; an open cube keeps every triangle.
TEST(ExactPenumbra, BackFacesOfClosedPartsOnly) {
    std::vector<dvec3> P;
    std::vector<uint32_t> I;
    const dvec3 outside(3.0, 0.4, 0.3), inside(0.5, 0.4, 0.3);
    for (bool inwards : {false, true}) {
        addCube(P, I, inwards, false);
        const int s = inwards ? -1 : 1;
        EXPECT_EQ(triangleFacing(P, I, outside), std::vector<int8_t>(12, int8_t(s))) << inwards;
        EXPECT_EQ(triangleFacing(P, I, inside), std::vector<int8_t>(12, int8_t(-s))) << inwards;
    }
    addCube(P, I, false, true);
    EXPECT_EQ(triangleFacing(P, I, outside), std::vector<int8_t>(10, 0));
    // Two cubes in one mesh, one closed and one open: each part on its own.
    addCube(P, I, false, false);
    std::vector<dvec3> P2;
    std::vector<uint32_t> I2;
    addCube(P2, I2, false, true);
    for (uint32_t i : I2) I.push_back(i + uint32_t(P.size()));
    for (const dvec3& q : P2) P.push_back(q + dvec3(5.0, 0.0, 0.0));
    const std::vector<int8_t> keep = triangleFacing(P, I, outside);
    ASSERT_EQ(keep.size(), 22u);
    EXPECT_EQ(std::vector<int8_t>(keep.begin(), keep.begin() + 12), std::vector<int8_t>(12, 1));
    EXPECT_EQ(std::vector<int8_t>(keep.begin() + 12, keep.end()), std::vector<int8_t>(10, 0));
}

// The union's speed-ups against the plain union, over every pixel: the bunny (closed, wound
// outwards, seen from outside: about half its candidates are back faces) and the closed-form scene
// with its square occluder as 16 x 16 squares (512 triangles sharing edges). Leaving the back
// faces out, or merging whole triangles along shared edges, gives the same region; after
// quantisation a shared edge clipped from its two triangles may round to neighbouring integers,
// and Clipper rounds the crossings of different edges, so V may move at the quantisation's scale
// (2^-29 of the light's edge along an edge: far below 1e-7).
TEST(ExactPenumbra, BackFacesAndMergingChangeNothing) {
    std::vector<Scene> scenes;
    PenumbraScene tiled = makePenumbraScene(64, 48);
    const AxisRect& r = tiled.occluder;
    tiled.scene.meshes[1] = makeGrid({0.5 * (r.x0 + r.x1), r.y, 0.5 * (r.z0 + r.z1)},
                                     {r.x1 - r.x0, 0, 0}, {0, 0, -(r.z1 - r.z0)}, 16, "occluder");
    finalizeScene(tiled.scene);
    scenes.push_back(tiled.scene);
    std::string why;
    if (const MeshPrimitive* bunny = cgalBunny(why)) {
        scenes.push_back(makeBunnyScene(*bunny, 64, 48));
        useLowRectLight(scenes.back());
    }
    for (const Scene& scene : scenes) {
        std::vector<std::vector<float>> planes;
        std::vector<ExactPenumbraStats> stats;
        // All on; back faces off; merging off.
        for (int variant : {0, 1, 2}) {
            OracleOptions o;
            o.penumbra.method = PenumbraMethod::Exact;
            o.penumbra.backFaces = variant != 1;
            o.penumbra.merge = variant != 2;
            const OracleResult res = runOracle(scene, o);
            stats.push_back(*res.stats.lights[0].area->exact);
            const float* v = res.image.channel(scene.lights[0].name + ".V");
            planes.emplace_back(v, v + res.image.pixelCount());
        }
        EXPECT_EQ(stats[1].backFacesTotal, 0u);
        double worst[2] = {0.0, 0.0};
        for (int k : {0, 1})
            for (size_t i = 0; i < planes[0].size(); ++i)
                worst[k] = std::max(
                    worst[k], std::fabs(double(planes[0][i]) - double(planes[size_t(k + 1)][i])));
        std::printf(
            "[ exact ] %s: %llu of %llu candidates left out as back faces; max |dV| "
            "against every back face %.3g, against no merging %.3g\n",
            scene.meshes[0].name.c_str(), (unsigned long long)stats[0].backFacesTotal,
            (unsigned long long)stats[0].candidatesTotal, worst[0], worst[1]);
        EXPECT_LT(worst[0], 1e-7);
        EXPECT_LT(worst[1], 1e-7);
    }
    // The bunny is closed: about half of its candidates are back faces.
    if (scenes.size() == 2) {
        OracleOptions o;
        o.penumbra.method = PenumbraMethod::Exact;
        const ExactPenumbraStats st = *runOracle(scenes[1], o).stats.lights[0].area->exact;
        EXPECT_GT(st.backFacesTotal, st.candidatesTotal / 4);
    }
}

// Every speed-up at once (the shortcuts, the back faces, merging with the slab's whole
// triangles, the covered check by winding numbers: occluder_union.h) against the plain per-pixel
// union of issue 31 (each triangle clipped to the pyramid, every back face, no shortcut), on every
// shipped scene with an area light and the bunny, every light, over the pixels exact in both runs:
// a rect light's V within 1e-7, a disk's or a sphere's bounds overlapping (their midpoints within
// the two half-widths, each about 1e-6, and 1e-7).
TEST(ExactPenumbra, FastUnionAgreesWithThePlainUnionOnShippedScenes) {
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const char* name : {"penumbra_square", "soft_chair", "sphere_light", "alpha_grate"}) {
        Scene s = loadScene(std::string(SO_SCENES_DIR) + "/" + name + ".scene.json");
        s.camera.width = 64;
        s.camera.height = 48;
        scenes.emplace_back(name, std::move(s));
    }
    std::string why;
    if (const MeshPrimitive* bunny = cgalBunny(why)) {
        scenes.emplace_back("bunny", makeBunnyScene(*bunny, 64, 48));
        useLowRectLight(scenes.back().second);
    }
    for (const auto& [name, scene] : scenes) {
        std::vector<OracleResult> runs;
        for (bool fast : {true, false}) {
            OracleOptions o;
            o.penumbra.method = PenumbraMethod::Exact;
            o.penumbra.shortcuts = o.penumbra.backFaces = o.penumbra.merge = fast;
            runs.push_back(runOracle(scene, o));
        }
        for (size_t l = 0; l < scene.lights.size(); ++l) {
            if (!runs[0].stats.lights[l].area || !runs[0].stats.lights[l].area->exact) continue;
            const std::string light = scene.lights[l].name;
            const bool bounded = areaLightKind(scene.lights[l].type).bounded();
            const float* v[2] = {runs[0].image.channel(light + ".V"),
                                 runs[1].image.channel(light + ".V")};
            const float* mask[2] = {runs[0].image.channel(light + "." + ch::kExact),
                                    runs[1].image.channel(light + "." + ch::kExact)};
            double worst = 0.0;
            size_t both = 0;
            for (size_t i = 0; i < runs[0].image.pixelCount(); ++i) {
                if (mask[0][i] != 1.0f || mask[1][i] != 1.0f) continue;
                ++both;
                const double d = std::fabs(double(v[0][i]) - double(v[1][i]));
                double allowed = 1e-7;
                if (bounded)
                    allowed += double(runs[0].image.channel(light + "." + ch::kBound)[i]) +
                               double(runs[1].image.channel(light + "." + ch::kBound)[i]);
                EXPECT_LE(d, allowed) << name << " " << light << " pixel " << i;
                worst = std::max(worst, d);
            }
            const ExactPenumbraStats& fast = *runs[0].stats.lights[l].area->exact;
            const ExactPenumbraStats& plain = *runs[1].stats.lights[l].area->exact;
            EXPECT_GT(both, runs[0].image.pixelCount() / 4) << name << " " << light;
            std::printf(
                "[ exact ] %s, %s: %zu pixels exact in both, max |V_fast - V_plain| %.3g; "
                "occluders %llu fast, %llu plain\n",
                name.c_str(), light.c_str(), both, worst, (unsigned long long)fast.occludersTotal,
                (unsigned long long)plain.occludersTotal);
        }
    }
}

// An independent float64 estimate with a standard error: `samples` i.i.d. uniform points of the
// light (SplitMix64, nothing of the oracle's Sobol sequences), each tested with the exact tracer's
// ray test from p, the ratio estimator's standard error by the delta method.
struct Estimate {
    double V = 0.0, stderr_ = 0.0;
};
Estimate randomEstimate(const ExactTracer& t, const RectLightShape& light, const dvec3& p,
                        const dvec3& n, TriangleId self, int samples, uint64_t seed) {
    SplitMix rng{seed};
    double sw = 0.0, swv = 0.0, sw2 = 0.0, sw2v = 0.0;
    for (int k = 0; k < samples; ++k) {
        const double u = double(rng.next() >> 11) * 0x1.0p-53,
                     v = double(rng.next() >> 11) * 0x1.0p-53;
        const dvec3 d = light.corner + u * light.edgeU + v * light.edgeV - p;
        const double r2 = glm::dot(d, d);
        const double w = std::max(0.0, glm::dot(n, d)) *
                         std::max(0.0, -glm::dot(light.emitNormal, d)) / (r2 * r2);
        if (w == 0.0) continue;
        const double lit = t.occluded(p, d, 1e-7, 1.0, self) ? 0.0 : 1.0;
        sw += w, swv += w * lit, sw2 += w * w, sw2v += w * w * lit;
    }
    Estimate e;
    if (sw == 0.0) return e;
    e.V = swv / sw;
    // Var(sum w (v - V)) / (sum w)^2 with (v - V)^2 = v (1 - 2V) + V^2.
    const double residual = sw2v * (1.0 - 2.0 * e.V) + sw2 * e.V * e.V;
    e.stderr_ = std::sqrt(std::max(0.0, residual)) / sw;
    return e;
}

// A real mesh (the Stanford bunny) under a rect light low over it, with pixels where the light is
// near the horizon: the exact V lies within the sampled pass's 95% interval at about the nominal
// rate at 4,096 spp (--penumbra both), and agrees with an independent float64 estimate of 10^6
// samples on a few pixels, within its error.
TEST(ExactPenumbra, BunnyWithinTheSampledIntervalsAndAnIndependentEstimate) {
    std::string why;
    const MeshPrimitive* bunny = cgalBunny(why);
    if (!bunny) GTEST_SKIP() << why;
    Scene scene = makeBunnyScene(*bunny, 80, 60);
    useLowRectLight(scene);
    OracleOptions o;
    o.area.fixedSpp = 4096;
    o.penumbra.method = PenumbraMethod::Both;
    const OracleResult r = runOracle(scene, o);
    const ExactPenumbraStats& st = *r.stats.lights[0].area->exact;
    const double n = double(st.pixelsExact), share = double(st.outsideInterval) / n;
    std::printf(
        "[ exact ] bunny: %llu exact pixels, %.4f outside the sampled 95%% interval, "
        "mean |V_exact - V| %.2e, occluders mean %.1f, max %llu; exact pass %.3f s, sampled "
        "pass (4,096 spp) %.3f s\n",
        (unsigned long long)st.pixelsExact, share, st.sumAbsDifference / n,
        double(st.occludersTotal) / n, (unsigned long long)st.occludersMax, st.seconds,
        r.stats.lights[0].area->seconds);
    ASSERT_GT(st.pixelsExact, 300u);
    // Nominal: at most 5% outside, give or take three binomial standard errors; and some outside,
    // or the intervals would be far wider than they say.
    EXPECT_LE(share, 0.05 + 3.0 * std::sqrt(0.05 * 0.95 / n));
    EXPECT_GT(st.outsideInterval, 0u);

    // The independent estimate, in world space at the stored P (its float rounding moves V by
    // far less than the estimate's error).
    const ChannelImage& img = r.image;
    const float* exact = img.channel("panel.exact");
    const float* Vexact = img.channel("panel.V_exact");
    std::vector<ExactTracer::MeshView> views;
    for (const MeshPrimitive& m : scene.meshes) views.push_back({&m.wsPositions, &m.indices});
    const ExactTracer t(views);
    const RectLightShape shape = rectLightShape(scene.lights[0]);
    std::vector<size_t> penumbra;
    for (size_t i = 0; i < img.pixelCount(); ++i)
        if (exact[i] == 1.0f && Vexact[i] > 0.05f && Vexact[i] < 0.95f) penumbra.push_back(i);
    ASSERT_GE(penumbra.size(), 4u);
    int checked = 0;
    for (size_t k = 0; k < 4; ++k) {
        const size_t i = penumbra[k * penumbra.size() / 4];
        const dvec3 p(img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]);
        const dvec3 nrm(img.channel(ch::kNX)[i], img.channel(ch::kNY)[i], img.channel(ch::kNZ)[i]);
        const TriangleId self{uint32_t(img.channel(ch::kMeshId)[i]),
                              uint32_t(img.channel(ch::kPrimId)[i])};
        const Estimate e = randomEstimate(t, shape, p, nrm, self, 1000000, 31 + i);
        std::printf("[ exact ] pixel %zu: V_exact %.5f, estimate %.5f +- %.5f (1 s.e.)\n", i,
                    double(Vexact[i]), e.V, e.stderr_);
        EXPECT_LT(std::fabs(double(Vexact[i]) - e.V), 4.0 * e.stderr_ + 1e-5) << i;
        ++checked;
    }
    EXPECT_EQ(checked, 4);
}

// The same exact image at any thread count, bit for bit (the pass sums in slot order): after the
// sampled pass (both) and finding its own pixels (exact), with the bunny's early stops.
TEST(ExactPenumbra, SameImageAtAnyThreadCount) {
    std::vector<Scene> scenes = {makePenumbraScene(64, 48).scene};
    std::string why;
    if (const MeshPrimitive* bunny = cgalBunny(why)) {
        scenes.push_back(makeBunnyScene(*bunny, 48, 36));
        useLowRectLight(scenes.back());
    }
    for (const Scene& scene : scenes)
        for (PenumbraMethod method : {PenumbraMethod::Both, PenumbraMethod::Exact}) {
            std::vector<std::vector<float>> images;
            std::vector<uint64_t> counts;
            for (int threads : {1, 2}) {
                OracleOptions o;
                o.threads = threads;
                o.penumbra.method = method;
                o.penumbra.allPixels = true;
                const OracleResult r = runOracle(scene, o);
                const std::string light = scene.lights[0].name;
                const float* v =
                    r.image.channel(light + (method == PenumbraMethod::Both ? ".V_exact" : ".V"));
                images.emplace_back(v, v + r.image.pixelCount());
                const ExactPenumbraStats& st = *r.stats.lights[0].area->exact;
                counts.insert(counts.end(), {st.pixelsExact, st.pixelsLit, st.pixelsCovered,
                                             st.occludersTotal, st.candidatesTotal});
            }
            EXPECT_EQ(images[0], images[1]);
            EXPECT_EQ(std::vector<uint64_t>(counts.begin(), counts.begin() + 5),
                      std::vector<uint64_t>(counts.begin() + 5, counts.end()));
        }
}

// --penumbra auto: per light, the method the probe estimates cheaper, and why. On soft_chair the
// window (a rect light over 212 triangles) is cheaper exact at the default target; the sphere bulb
// is probed the same way (the exact pass bounds it) and runs the method chosen. The choice counts
// work, so it is the same at any thread count; and where sampling is almost free (target 0.5, a
// few samples a pixel) against a dense mesh's pyramids, the probe picks sampling.
// auto is the default of the oracle and of the API; exact wins ties and estimates up to the margin
// over sampling's (the cost model's errors), and only those.
TEST(ExactPenumbra, AutoIsTheDefaultAndExactWinsWithinTheMargin) {
    EXPECT_EQ(OracleOptions{}.penumbra.method, PenumbraMethod::Auto);
    EXPECT_EQ(cheaperPenumbraMethod(1.0, 1.0), PenumbraMethod::Exact);
    EXPECT_EQ(cheaperPenumbraMethod(1.4, 1.0), PenumbraMethod::Exact);
    EXPECT_EQ(cheaperPenumbraMethod(kPenumbraExactMargin, 1.0), PenumbraMethod::Exact);
    EXPECT_EQ(cheaperPenumbraMethod(1.6, 1.0), PenumbraMethod::Sampled);
    EXPECT_EQ(cheaperPenumbraMethod(0.0, 0.0), PenumbraMethod::Exact);
}

TEST(ExactPenumbra, AutoChoosesPerLightAndSaysWhy) {
    Scene chair = loadScene(std::string(SO_SCENES_DIR) + "/soft_chair.scene.json");
    chair.camera.width = 96;
    chair.camera.height = 72;
    std::vector<PenumbraChoice> choices;
    for (int threads : {1, 2}) {
        OracleOptions o;
        o.threads = threads;
        o.penumbra.method = PenumbraMethod::Auto;
        const OracleResult r = runOracle(chair, o);
        ASSERT_EQ(r.stats.lights.size(), 2u);
        for (const OracleLightStats& l : r.stats.lights) {
            ASSERT_TRUE(l.choice.has_value()) << l.name;
            choices.push_back(*l.choice);
            std::printf("[ exact ] auto, %s: %s (%s)\n", l.name.c_str(),
                        penumbraMethodName(l.choice->chosen), l.choice->reason.c_str());
        }
        const OracleLightStats& window = r.stats.lights[0];
        EXPECT_EQ(window.choice->chosen, PenumbraMethod::Exact);
        EXPECT_GT(window.choice->probePoints, 50u);
        EXPECT_GT(window.choice->probeRays, 0u);
        ASSERT_TRUE(window.area->exact.has_value());
        EXPECT_EQ(window.area->exact->method, PenumbraMethod::Exact);
        const OracleLightStats& bulb = r.stats.lights[1];
        EXPECT_EQ(bulb.choice->reason.find("exact estimated at"), 0u) << bulb.choice->reason;
        EXPECT_GT(bulb.choice->probePoints, 50u);
        EXPECT_GT(bulb.choice->probeCandidates, 0u);
        // The gathering octagon's sides (disk_exact.h): the contour's cost is in the estimate.
        EXPECT_GT(bulb.choice->probeBoundSides, 0u);
        EXPECT_EQ(window.choice->probeBoundSides, 0u);
        EXPECT_EQ(bulb.area->exact.has_value(), bulb.choice->chosen == PenumbraMethod::Exact);
        if (bulb.area->exact) {
            EXPECT_EQ(bulb.area->exact->errorKind, "bound");
        }
    }
    for (size_t k = 0; k < 2; ++k) {
        EXPECT_EQ(choices[k].probeRays, choices[k + 2].probeRays);
        EXPECT_EQ(choices[k].probeOccluders, choices[k + 2].probeOccluders);
        EXPECT_EQ(choices[k].reason, choices[k + 2].reason);
    }
    std::string why;
    const MeshPrimitive* bunny = cgalBunny(why);
    if (!bunny) GTEST_SKIP() << why;
    Scene b = makeBunnyScene(*bunny, 64, 48);
    useLowRectLight(b);
    OracleOptions o;
    o.penumbra.method = PenumbraMethod::Auto;
    o.area.fixedSpp = 16;
    const OracleResult r = runOracle(b, o);
    const PenumbraChoice& c = *r.stats.lights[0].choice;
    std::printf("[ exact ] auto, bunny at 16 spp: %s (%s)\n", penumbraMethodName(c.chosen),
                c.reason.c_str());
    EXPECT_EQ(c.chosen, PenumbraMethod::Sampled);
    EXPECT_FALSE(r.stats.lights[0].area->exact.has_value());
}

// --verify on --penumbra exact: the exact pixels (no samples, stderr 0) are compared with the
// independent re-trace's own estimate like any measured pixel, not passed over as skipped.
TEST(ExactPenumbra, VerifyChecksTheExactPixels) {
    const PenumbraScene s = makePenumbraScene(64, 48);
    OracleOptions o;
    o.penumbra.method = PenumbraMethod::Exact;
    o.verify.pixels = 100;
    const OracleResult r = runOracle(s.scene, o);
    ASSERT_TRUE(r.stats.verify.has_value());
    const LightVerification& l = r.stats.verify->lights.at(0);
    EXPECT_EQ(l.disagree, 0u);
    EXPECT_GT(l.agree, l.checked * 9 / 10);
}

// The command line: the flags by name, a bad name one line naming its flag.
TEST(ExactPenumbra, CommandLineFlags) {
    const std::string scene = std::string(SO_SCENES_DIR) + "/penumbra_square.scene.json";
    const std::string out = ::testing::TempDir() + "so_exact_cli";
    const RunResult bad = run("trace " + scene + " --out " + out + " --penumbra exakt");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_EQ(
        bad.stderrText,
        "command line: --penumbra: unknown value \"exakt\" (valid: sampled, exact, both, auto)\n");
    EXPECT_EQ(run("trace " + scene + " --out " + out + " --exact-pixels some").exitCode, 2);
    const RunResult ok = run("trace " + scene + " --out " + out +
                             " --width 48 --height 36 --quiet --penumbra both --exact-pixels all");
    ASSERT_EQ(ok.exitCode, 0) << ok.stderrText;
    const ChannelImage img = readExr(out + "/oracle.exr");
    EXPECT_NE(img.channel("panel.V_exact"), nullptr);
    EXPECT_NE(img.channel("panel.exact"), nullptr);
}

}  // namespace
}  // namespace so::test
