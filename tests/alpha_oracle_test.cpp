// Alpha-tested occluders in the oracle against closed forms (docs/oracle.md, "Alpha-tested
// geometry"): a checker-masked square under a point light casts an exact checker shadow and shows
// the floor through its holes; a grate of bars under a rect light gives Lambert's exact V per
// pixel (the light minus the bars' shadows on it); without the "alpha" effect the mask is ignored.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/alpha_mask.h"
#include "core/channels.h"
#include "lambert.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

// A square at height y over x, z in [-h, h], its uv running with x and z from 0 to 1.
MeshPrimitive makeMaskedSquare(double y, double h, int cells, const AlphaMask& mask) {
    MeshPrimitive m = makeGrid({0, y, 0}, {2 * h, 0, 0}, {0, 0, -2 * h}, cells, "masked");
    for (const glm::dvec3& p : m.wsPositions)
        m.uvs.push_back(glm::vec2(float((p.x + h) / (2 * h)), float((p.z + h) / (2 * h))));
    m.alpha = mask;
    return m;
}

// n x n checker, texel (0, 0) opaque.
AlphaTexture checker(int n) {
    AlphaTexture t;
    t.name = "checker";
    t.width = t.height = n;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) t.alpha.push_back(((i + j) & 1) ? 0.0f : 1.0f);
    return t;
}

struct CheckerScene {
    static constexpr double kY = 2.0, kHalf = 1.0;
    static constexpr int kCells = 8;
    glm::dvec3 light{0.3125, 6.0, 0.1875};
    Scene scene;
};

CheckerScene makeCheckerScene(bool alphaEffect) {
    CheckerScene c;
    Scene& s = c.scene;
    s.alphaTextures.push_back(checker(CheckerScene::kCells));
    AlphaMask mask;
    mask.texture = 0;
    s.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 4, "floor"));
    s.meshes.push_back(makeMaskedSquare(CheckerScene::kY, CheckerScene::kHalf, 2, mask));
    s.lights.push_back({"key", LightType::Point, c.light, {0, -1, 0}, 0, 0});
    s.effects =
        alphaEffect ? std::vector<std::string>{"hard", "alpha"} : std::vector<std::string>{"hard"};
    s.camera.wsEye = {0.5, 7.0, 3.0};
    s.camera.wsTarget = {0.0, 0.0, 0.0};
    s.camera.vfovDeg = 30;
    s.camera.width = s.camera.height = 160;
    finalizeScene(s);
    return c;
}

// Where the square's plane is crossed by the segment a -> b: its uv, and how far (in cells) it
// is from the nearest cell edge; nullopt if the segment misses the square.
struct SquareCrossing {
    double u, v, edgeDistance;
};
std::optional<SquareCrossing> crossing(const glm::dvec3& a, const glm::dvec3& b) {
    const double t = (CheckerScene::kY - a.y) / (b.y - a.y);
    if (!(t > 0.0 && t < 1.0)) return std::nullopt;
    const glm::dvec3 q = a + t * (b - a);
    const double h = CheckerScene::kHalf;
    if (std::fabs(q.x) > h || std::fabs(q.z) > h) return std::nullopt;
    SquareCrossing c{(q.x + h) / (2 * h), (q.z + h) / (2 * h), 0.0};
    const double cu = c.u * CheckerScene::kCells, cv = c.v * CheckerScene::kCells;
    c.edgeDistance = std::min(std::fabs(cu - std::round(cu)), std::fabs(cv - std::round(cv)));
    return c;
}

bool checkerOpaque(double u, double v) {
    const int i = std::min(int(u * CheckerScene::kCells), CheckerScene::kCells - 1);
    const int j = std::min(int(v * CheckerScene::kCells), CheckerScene::kCells - 1);
    return ((i + j) & 1) == 0;
}

glm::dvec3 pixelPoint(const ChannelImage& img, size_t i) {
    return {img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]};
}

// Float channels hold the hit point to ~1e-7 of the scene: a crossing closer than this (in cells)
// to a cell edge is not judged.
constexpr double kEdgeBand = 1e-4;

TEST(AlphaOracle, CheckerSquareCastsAnExactCheckerShadow) {
    const CheckerScene c = makeCheckerScene(true);
    const OracleResult r = runOracle(c.scene, [] {
        OracleOptions o;
        return o;
    }());
    const ChannelImage& img = r.image;
    const float* A = img.channel(ch::kHit);
    const float* V = img.channel("key.V");
    const glm::dvec3 eye = c.scene.camera.wsEye;
    size_t floorChecked = 0, floorWrong = 0, shadowed = 0, squareSeen = 0, squareWrong = 0;
    size_t throughHoles = 0, holesWrong = 0, band = 0;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        const glm::dvec3 p = pixelPoint(img, i);
        if (std::fabs(p.y - CheckerScene::kY) < 1e-3) {  // the camera sees the square here
            ++squareSeen;
            const double h = CheckerScene::kHalf;
            squareWrong += !checkerOpaque((p.x + h) / (2 * h), (p.z + h) / (2 * h));
            continue;
        }
        // A floor pixel: the eye's ray, if it crossed the square, crossed it at a hole.
        if (auto e = crossing(eye, p)) {
            if (e->edgeDistance < kEdgeBand) {
                ++band;
                continue;
            }
            ++throughHoles;
            holesWrong += checkerOpaque(e->u, e->v);
        }
        const auto s = crossing(p, c.light);
        if (s && s->edgeDistance < kEdgeBand) {
            ++band;
            continue;
        }
        const float expected = s && checkerOpaque(s->u, s->v) ? 0.0f : 1.0f;
        ++floorChecked;
        shadowed += expected == 0.0f;
        floorWrong += V[i] != expected;
    }
    std::printf(
        "[ alpha ] checker: %zu floor px (%zu in the checker shadow), %zu wrong; %zu px see the "
        "square, %zu of them at a hole; %zu floor px seen through holes, %zu wrong; %zu within "
        "%.0e cells of an edge not judged; %llu primary and %llu shadow alpha tests\n",
        floorChecked, shadowed, floorWrong, squareSeen, squareWrong, throughHoles, holesWrong, band,
        kEdgeBand, (unsigned long long)r.stats.primaryAlphaTests,
        (unsigned long long)r.stats.shadowAlphaTests);
    EXPECT_GT(shadowed, 500u);
    EXPECT_GT(throughHoles, 300u);
    EXPECT_GT(squareSeen, 300u);
    EXPECT_EQ(floorWrong, 0u);
    EXPECT_EQ(squareWrong, 0u);
    EXPECT_EQ(holesWrong, 0u);
    EXPECT_LT(band, floorChecked / 50);
    EXPECT_GT(r.stats.primaryAlphaTests, 0u);
    EXPECT_GT(r.stats.shadowAlphaTests, 0u);
    ASSERT_EQ(r.stats.lights.size(), 1u);
    EXPECT_EQ(r.stats.lights[0].hard->alphaTests, r.stats.shadowAlphaTests);
}

// Without "alpha" in the effects the mask is ignored: the square is opaque, and nothing is tested.
TEST(AlphaOracle, WithoutTheEffectTheSquareIsOpaque) {
    const CheckerScene c = makeCheckerScene(false);
    OracleOptions o;
    const OracleResult r = runOracle(c.scene, o);
    const float* A = r.image.channel(ch::kHit);
    const float* V = r.image.channel("key.V");
    size_t checked = 0, wrong = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        const glm::dvec3 p = pixelPoint(r.image, i);
        if (std::fabs(p.y) > 1e-3) continue;
        const auto s = crossing(p, c.light);
        if (s && s->edgeDistance < kEdgeBand) continue;
        ++checked;
        wrong += V[i] != (s ? 0.0f : 1.0f);
    }
    EXPECT_GT(checked, 1000u);
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(r.stats.primaryAlphaTests + r.stats.shadowAlphaTests, 0u);
}

// A constant-alpha mask below its cutoff removes the mesh for every ray.
TEST(AlphaOracle, ConstantAlphaBelowTheCutoffRemovesTheMesh) {
    CheckerScene c = makeCheckerScene(true);
    c.scene.meshes[1].alpha->texture = -1;
    c.scene.meshes[1].alpha->factor = 0.25f;
    c.scene.meshes[1].uvs.clear();
    OracleOptions o;
    const OracleResult r = runOracle(c.scene, o);
    const float* A = r.image.channel(ch::kHit);
    const float* V = r.image.channel("key.V");
    size_t hits = 0, notFloor = 0, dark = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        ++hits;
        notFloor += std::fabs(pixelPoint(r.image, i).y) > 1e-3;
        dark += V[i] != 1.0f;
    }
    EXPECT_GT(hits, 1000u);
    EXPECT_EQ(notFloor, 0u);
    EXPECT_EQ(dark, 0u);
}

// A grate: 16 texel columns, even ones opaque (bars 0.25 wide, 50% open), at height 1.5 over
// [-2, 2]^2, under a 1 x 1 rect light at height 4. For a floor point p with |x|, |z| <= 1 the bars'
// shadows on the light's plane are x-intervals spanning the light's whole depth, so the visible
// light is a set of full-depth strips and V(p) is exact by Lambert's formula.
struct GrateScene {
    static constexpr double kY = 1.5, kHalf = 2.0;
    static constexpr int kColumns = 16;
    AxisRect light{4.0, -0.5, 0.5, -0.5, 0.5};
    Scene scene;
};

GrateScene makeGrateScene(int size) {
    GrateScene g;
    Scene& s = g.scene;
    AlphaTexture t;
    t.name = "grate";
    t.width = GrateScene::kColumns;
    t.height = 1;
    for (int i = 0; i < t.width; ++i) t.alpha.push_back(i % 2 == 0 ? 1.0f : 0.0f);
    s.alphaTextures.push_back(t);
    AlphaMask mask;
    mask.texture = 0;
    s.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 4, "floor"));
    s.meshes.push_back(makeMaskedSquare(GrateScene::kY, GrateScene::kHalf, 1, mask));
    Light l;
    l.name = "panel";
    l.type = LightType::Rect;
    l.wsPosition = {0.0, g.light.y, 0.0};
    l.wsU = {1, 0, 0};
    l.wsV = {0, 0, 1};  // cross(u, v) points down
    s.lights = {l};
    s.effects = {"hard", "penumbra", "alpha"};
    // Below the grate, looking down at the floor under it.
    s.camera.wsEye = {0.0, 1.0, 2.5};
    s.camera.wsTarget = {0.0, 0.0, 0.0};
    s.camera.vfovDeg = 60;
    s.camera.width = s.camera.height = size;
    finalizeScene(s);
    return g;
}

// Exact V at a floor point p (|x|, |z| <= 1) under the grate.
double exactGrateV(const GrateScene& g, const glm::dvec3& p) {
    const glm::dvec3 up(0, 1, 0);
    const double total = polygonIrradiance(p, up, axisRectPolygon(g.light), {0, -1, 0});
    // Bar k covers x in [x0, x0 + w] at the grate's height; seen from p it shadows the light's
    // plane over p.x + (x - p.x) * s, s = light height / grate height (p.y = 0).
    const double s = (g.light.y - p.y) / (GrateScene::kY - p.y);
    const double w = 2 * GrateScene::kHalf / GrateScene::kColumns;
    std::vector<std::pair<double, double>> blocked;
    for (int k = 0; k < GrateScene::kColumns; k += 2) {
        const double x0 = -GrateScene::kHalf + k * w;
        blocked.push_back({p.x + (x0 - p.x) * s, p.x + (x0 + w - p.x) * s});
    }
    double visible = 0.0, x = g.light.x0;
    for (const auto& [b0, b1] : blocked) {  // in increasing x, disjoint
        const double open1 = std::min(b0, g.light.x1);
        if (open1 > x)
            visible += polygonIrradiance(
                p, up, axisRectPolygon({g.light.y, x, open1, g.light.z0, g.light.z1}), {0, -1, 0});
        x = std::max(x, b1);
    }
    if (g.light.x1 > x)
        visible += polygonIrradiance(
            p, up, axisRectPolygon({g.light.y, x, g.light.x1, g.light.z0, g.light.z1}), {0, -1, 0});
    return visible / total;
}

TEST(AlphaOracle, GrateUnderARectLightMatchesLambertWithinStatedIntervals) {
    const GrateScene g = makeGrateScene(96);
    OracleOptions o;
    const OracleResult r = runOracle(g.scene, o);
    const float* A = r.image.channel(ch::kHit);
    const float* V = r.image.channel("panel.V");
    const float* SE = r.image.channel("panel.stderr");
    size_t n = 0, covered = 0;
    double absSum = 0.0, meanV = 0.0, meanExact = 0.0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (A[i] == 0.0f) continue;
        const glm::dvec3 p = pixelPoint(r.image, i);
        if (std::fabs(p.y) > 1e-3 || std::fabs(p.x) > 1.0 || std::fabs(p.z) > 1.0) continue;
        const double e = exactGrateV(g, p);
        ++n;
        absSum += std::fabs(V[i] - e);
        meanV += V[i];
        meanExact += e;
        covered += std::fabs(V[i] - e) <= ch::kStdErrQuantile95 * SE[i] + 1e-6;
    }
    ASSERT_GT(n, 1500u);
    const double coverage = double(covered) / double(n);
    std::printf(
        "[ alpha ] grate (50%% open) under a rect light: %zu floor px, mean V %.4f (exact %.4f), "
        "mean |V - exact| %.4f, %.1f%% within the stated 95%% interval; %llu shadow alpha tests\n",
        n, meanV / double(n), meanExact / double(n), absSum / double(n), 100.0 * coverage,
        (unsigned long long)r.stats.shadowAlphaTests);
    EXPECT_LT(absSum / double(n), 0.01);
    EXPECT_GT(coverage, 0.9);
    EXPECT_NEAR(meanV / double(n), meanExact / double(n), 0.005);
}

// The alpha test changes nothing in the determinism contract.
TEST(AlphaOracle, BitIdenticalAtAnyThreadCount) {
    const CheckerScene c = makeCheckerScene(true);
    const ChannelImage one = runQuiet(c.scene, 1), four = runQuiet(c.scene, 4);
    for (const std::string& name : one.names())
        ASSERT_EQ(
            0, std::memcmp(one.channel(name), four.channel(name), one.pixelCount() * sizeof(float)))
            << name;
}

}  // namespace
}  // namespace so::test
