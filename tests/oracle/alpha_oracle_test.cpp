// Alpha-tested occluders in the oracle against closed forms (docs/oracle.md, "Alpha-tested
// geometry"): a checker-masked square under a point light casts an exact checker shadow and shows
// the floor through its holes; a grate of bars under a rect light gives Lambert's exact V per
// pixel (the light minus the bars' shadows on it); without the "alpha" effect the mask is ignored.
// The independent re-trace of `--verify` tests the masks in double (oracle/exact_alpha.h): it
// agrees with the oracle, finds a wrong cutoff, and calls a texel-boundary crossing ambiguous;
// the exact penumbra pass answers where no alpha-tested triangle cuts a pixel's pyramid.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/alpha_mask.h"
#include "core/channels.h"
#include "core/lights/make_light.h"
#include "lambert.h"
#include "oracle/accel.h"
#include "oracle/exact_alpha.h"
#include "oracle/exact_scene.h"
#include "oracle/surface_buffer.h"
#include "oracle/verify.h"
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
    s.lights.push_back(pointLight("key", c.light));
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
    // cross(u, v) points down
    s.lights = {rectLight("panel", {0.0, g.light.y, 0.0}, {1, 0, 0}, {0, 0, 1})};
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

// ---- --verify with alpha masks (oracle/exact_alpha.h) -----------------------------------------

// The oracle's V of a light, verified at every pixel against `truth` (the scene the reference
// tests); the oracle ran on `traced`, which may differ from it on purpose.
LightVerification verifyEveryPixel(const Scene& traced, const Scene& truth, const float* V,
                                   size_t light = 0) {
    EmbreeDevice device;
    const Accel accel(traced, device);
    OracleOptions o;
    const Camera camera(effectiveCamera(traced, o));
    const SurfaceBuffer sb = tracePrimary(accel, camera, nullptr);
    VerifyOptions vo;
    vo.pixels = camera.width() * camera.height();
    const Verifier verifier(truth, accel.frame(), &camera, vo, 0);
    return verifier.verifyLight(truth.lights[light], uint32_t(light), false, sb, V, nullptr,
                                nullptr);
}

// A checker of alpha 0.75 (cells the oracle keeps at cutoff 0.5) and 0.25 (holes).
CheckerScene makeGreyCheckerScene() {
    CheckerScene c = makeCheckerScene(true);
    for (float& a : c.scene.alphaTextures[0].alpha) a = a > 0.5f ? 0.75f : 0.25f;
    return c;
}

// The checker square under a point light: every pixel re-traced, with the masks, agrees; the
// oracle run with a wrong cutoff (0.8: the square all holes) is caught at every pixel whose shadow
// ray or primary ray meets an opaque cell.
TEST(AlphaVerify, CheckerAgreesAndAWrongCutoffIsCaught) {
    const CheckerScene c = makeGreyCheckerScene();
    const ChannelImage good = runQuiet(c.scene);
    const LightVerification ok = verifyEveryPixel(c.scene, c.scene, good.channel("key.V"));
    std::printf(
        "[ alpha ] verify, checker: %llu checked, %llu agree, %llu ambiguous (%llu alpha), "
        "%llu disagree\n",
        (unsigned long long)ok.checked, (unsigned long long)ok.agree,
        (unsigned long long)ok.ambiguous, (unsigned long long)ok.alphaAmbiguous,
        (unsigned long long)ok.disagree);
    EXPECT_GT(ok.checked, 15000u);
    EXPECT_EQ(ok.disagree, 0u);
    EXPECT_LT(ok.ambiguous, ok.checked / 1000);

    Scene broken = c.scene;
    broken.meshes[1].alpha->cutoff = 0.8f;
    const ChannelImage bad = runQuiet(broken);
    const LightVerification caught = verifyEveryPixel(broken, c.scene, bad.channel("key.V"));
    size_t shadow = 0, primary = 0;
    for (const VerifyDisagreement& d : caught.disagreements) {
        shadow += d.kind == "shadow" && d.oracleV == 1.0 && d.referenceV == 0.0;
        primary += d.kind == "primary";
    }
    std::printf(
        "[ alpha ] verify, checker traced at cutoff 0.8: %llu disagreements (%zu shadow "
        "rays lit through opaque cells, %zu primary rays through them)\n",
        (unsigned long long)caught.disagree, shadow, primary);
    EXPECT_GT(shadow, 500u);
    EXPECT_GT(primary, 300u);
    EXPECT_EQ(shadow + primary, caught.disagree);
}

// Straight down through a texel boundary of the checker (x = 0.25, between cells 4 and 5, one
// opaque and one a hole in every row): the centre column of an odd-width camera above x = 0.25
// has its floor points there, so their shadow rays cross the square on the boundary. Flipped V
// there is ambiguous (an alpha test within its margins), never a disagreement; flipped V
// elsewhere is a disagreement.
TEST(AlphaVerify, TexelBoundaryCrossingIsAmbiguousNotADisagreement) {
    CheckerScene c = makeGreyCheckerScene();
    Scene& s = c.scene;
    s.lights = {directionalLight("sun", {0, -1, 0})};
    s.camera.wsEye = {0.25, 7.0, 3.0};
    s.camera.wsTarget = {0.25, 0.0, 0.0};
    s.camera.width = s.camera.height = 81;
    finalizeScene(s);
    const ChannelImage img = runQuiet(s);
    const float* A = img.channel(ch::kHit);
    std::vector<float> V(img.channel("sun.V"), img.channel("sun.V") + img.pixelCount());
    const LightVerification clean = verifyEveryPixel(s, s, V.data());
    EXPECT_EQ(clean.disagree, 0u);
    // The centre column's floor pixels under the square, and as many elsewhere under it (not in
    // the centre row: the camera looks at z = 0, another texel boundary).
    std::set<std::pair<int, int>> onBoundary, elsewhere;
    for (int y = 0; y < 81; ++y)
        for (int x : {40, 20}) {
            const size_t i = size_t(y) * 81 + size_t(x);
            if (x == 20 && y == 40) continue;
            const glm::dvec3 p = pixelPoint(img, i);
            if (A[i] == 0.0f || std::fabs(p.y) > 1e-3 || std::fabs(p.z) > 0.95) continue;
            V[i] = 1.0f - V[i];
            (x == 40 ? onBoundary : elsewhere).insert({x, y});
        }
    ASSERT_GT(onBoundary.size(), 5u);
    ASSERT_GT(elsewhere.size(), 5u);
    const LightVerification l = verifyEveryPixel(s, s, V.data());
    std::set<std::pair<int, int>> found;
    for (const VerifyDisagreement& d : l.disagreements) found.insert({d.x, d.y});
    std::printf(
        "[ alpha ] texel boundary: %zu flipped on it, %llu alpha-ambiguous; %zu flipped "
        "elsewhere, %zu disagreements\n",
        onBoundary.size(), (unsigned long long)l.alphaAmbiguous, elsewhere.size(), found.size());
    EXPECT_EQ(found, elsewhere);
    EXPECT_GE(l.alphaAmbiguous, onBoundary.size());
}

// The lookup itself: nearest at and off a texel boundary, bilinear near the cutoff, and the wraps.
TEST(AlphaVerify, LookupMarginsAndWraps) {
    AlphaTexture t = checker(8);
    AlphaMask m;
    m.texture = 0;
    const glm::dvec2 tiny(1e-6);
    // Texel coordinate 5.0: texels 4 (a hole in row 0) and 5 (opaque) meet.
    EXPECT_TRUE(exact_alpha::lookup(t, m, {5.0, 0.5}, tiny).ambiguous);
    EXPECT_TRUE(exact_alpha::lookup(t, m, {5.0 - 1e-7, 0.5}, tiny).ambiguous);
    const AlphaAnswer inside = exact_alpha::lookup(t, m, {4.5, 0.5}, tiny);
    EXPECT_TRUE(inside.present);
    EXPECT_FALSE(inside.ambiguous);
    EXPECT_FALSE(exact_alpha::lookup(t, m, {5.5, 0.5}, tiny).present);
    EXPECT_FALSE(exact_alpha::lookup(t, m, {5.5, 0.5}, tiny).ambiguous);
    // Stripes (columns 0-3 opaque, 4-7 holes): a boundary between two texels that decide alike
    // is not ambiguous; one between an opaque and a hole texel is.
    AlphaTexture stripes = t;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) stripes.alpha[size_t(j * 8 + i)] = i < 4 ? 1.0f : 0.0f;
    EXPECT_FALSE(exact_alpha::lookup(stripes, m, {2.0, 3.0}, tiny).ambiguous);
    EXPECT_TRUE(exact_alpha::lookup(stripes, m, {4.0, 3.0}, tiny).ambiguous);
    // Bilinear: alpha 0.5 halfway between the centres of texels 3 (1) and 4 (0) of the stripes.
    m.filter = TextureFilter::Bilinear;
    EXPECT_TRUE(exact_alpha::lookup(stripes, m, {4.0, 3.5}, tiny).ambiguous);
    EXPECT_FALSE(exact_alpha::lookup(stripes, m, {3.9, 3.5}, tiny).ambiguous);
    EXPECT_TRUE(exact_alpha::lookup(stripes, m, {3.9, 3.5}, tiny).present);
    EXPECT_FALSE(exact_alpha::lookup(stripes, m, {4.1, 3.5}, tiny).present);
    // Too uncertain to know the texel: ambiguous outright.
    m.filter = TextureFilter::Nearest;
    EXPECT_TRUE(exact_alpha::lookup(stripes, m, {2.0, 3.0}, glm::dvec2(3.0)).ambiguous);
    // Wraps, in integers, as OpenGL: repeat, clamp, mirrored repeat.
    EXPECT_EQ(exact_alpha::wrapIndex(-1, 8, TextureWrap::Repeat), 7);
    EXPECT_EQ(exact_alpha::wrapIndex(17, 8, TextureWrap::Repeat), 1);
    EXPECT_EQ(exact_alpha::wrapIndex(-3, 8, TextureWrap::ClampToEdge), 0);
    EXPECT_EQ(exact_alpha::wrapIndex(9, 8, TextureWrap::ClampToEdge), 7);
    EXPECT_EQ(exact_alpha::wrapIndex(8, 8, TextureWrap::MirroredRepeat), 7);
    EXPECT_EQ(exact_alpha::wrapIndex(-1, 8, TextureWrap::MirroredRepeat), 0);
    EXPECT_EQ(exact_alpha::wrapIndex(16, 8, TextureWrap::MirroredRepeat), 0);
    for (TextureWrap w :
         {TextureWrap::Repeat, TextureWrap::ClampToEdge, TextureWrap::MirroredRepeat})
        for (int i = -40; i < 40; ++i)
            EXPECT_EQ(exact_alpha::wrapIndex(i, 8, w), wrapTexel(double(i), 8, w)) << i;
}

// The shipped grate through the library at a small size: both lights (the sun hard, the panel
// sampled) verified at every pixel with a hit, no disagreement.
TEST(AlphaVerify, ShippedGrateAgreesAtEveryPixel) {
    const Scene scene = loadScene(std::string(SO_SCENES_DIR) + "/alpha_grate.scene.json");
    OracleOptions o;
    o.width = 80;
    o.height = 60;
    o.verify.pixels = 80 * 60;
    o.verify.areaSamples = 1024;
    const OracleResult r = runOracle(scene, o);
    ASSERT_TRUE(r.stats.verify.has_value());
    ASSERT_EQ(r.stats.verify->lights.size(), 2u);
    for (const LightVerification& l : r.stats.verify->lights) {
        std::printf(
            "[ alpha ] verify, alpha_grate %s: %llu checked, %llu agree, %llu ambiguous "
            "(%llu alpha), %llu disagree (%.2f s)\n",
            l.light.c_str(), (unsigned long long)l.checked, (unsigned long long)l.agree,
            (unsigned long long)l.ambiguous, (unsigned long long)l.alphaAmbiguous,
            (unsigned long long)l.disagree, l.seconds);
        EXPECT_GT(l.checked, 2000u) << l.light;
        EXPECT_EQ(l.disagree, 0u) << l.light;
    }
    EXPECT_GT(r.stats.shadowAlphaTests, 0u);
}

// ---- the exact penumbra pass with alpha ------------------------------------------------------

// The grate under the rect light with --penumbra both --exact-pixels all: pixels whose pyramid
// holds a grate triangle keep their sampled V (counted as alpha_tested); the others are exact,
// and bit for bit what the same pass gives with the grate opaque (same triangles in the pyramid).
TEST(AlphaExactPenumbra, PixelsClearOfTheGrateAreExactTheOthersKeepSampledV) {
    GrateScene g = makeGrateScene(64);
    g.scene.camera.wsEye = {0.0, 1.2, 6.0};  // wider: floor beyond the grate's shadow too
    finalizeScene(g.scene);
    OracleOptions o;
    o.penumbra.method = PenumbraMethod::Both;
    o.penumbra.allPixels = true;
    const OracleResult r = runOracle(g.scene, o);
    Scene opaque = g.scene;
    opaque.effects = {"hard", "penumbra"};
    const OracleResult ro = runOracle(opaque, o);
    const ExactPenumbraStats& e = *r.stats.lights.at(0).area->exact;
    const ExactPenumbraStats& eo = *ro.stats.lights.at(0).area->exact;
    EXPECT_TRUE(e.notApplied.empty()) << e.notApplied;
    const float* mask = r.image.channel("panel.exact");
    const float* Vx = r.image.channel("panel.V_exact");
    const float* V = r.image.channel("panel.V");
    const float* maskO = ro.image.channel("panel.exact");
    const float* VxO = ro.image.channel("panel.V_exact");
    const float* spp = r.image.channel("panel.spp");
    uint64_t exact = 0, kept = 0, lit = 0, mismatched = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (!(spp[i] > 0.0f)) continue;
        if (mask[i] == 1.0f) {
            ++exact;
            mismatched += maskO[i] != 1.0f || Vx[i] != VxO[i];
            lit += Vx[i] == 1.0f;  // nothing but the floor: the whole light seen
        } else {
            ++kept;
            mismatched += Vx[i] != V[i];
        }
    }
    std::printf(
        "[ alpha ] exact pass on the grate: %llu px exact (%llu fully lit), %llu kept "
        "sampled (alpha_tested %llu); opaque grate: %llu exact\n",
        (unsigned long long)exact, (unsigned long long)lit, (unsigned long long)kept,
        (unsigned long long)e.pixelsAlphaTested, (unsigned long long)eo.pixelsExact);
    EXPECT_EQ(mismatched, 0u);
    EXPECT_EQ(e.pixelsExact, exact);
    EXPECT_EQ(e.pixelsAlphaTested, kept);
    EXPECT_EQ(e.pixelsTooManyOccluders, 0u);
    EXPECT_GT(exact, 200u);
    EXPECT_GT(kept, 200u);
    EXPECT_EQ(lit, exact);  // the only occluder is the grate
    EXPECT_EQ(eo.pixelsAlphaTested, 0u);
    EXPECT_EQ(eo.pixelsExact, exact + kept);
}

}  // namespace
}  // namespace so::test
