// Alpha-tested occluders on the raster path (issue 17; ctest label "gl", skipped with the reason
// where no EGL display or GL 4.5 context can be had). One scene built in code: a 2 x 2 quad with an
// 8 x 8 checkerboard alpha 1 unit above a floor, under a point light. Every pixel's expected
// answer is computed on the CPU in closed form (the segment to the light, or from the eye, through
// the quad's plane, then core/alpha_mask.h's test), so the raster path's alpha test is checked per
// pixel in the shadow pass and in the camera pass.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "core/alpha_mask.h"
#include "core/channels.h"
#include "core/lights/make_light.h"
#include "gl_test_context.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;

// The scene: floor y = 0 over [-3, 3]^2 (mesh 0, facing up), the quad y = 1 over [-1, 1]^2
// (mesh 1, facing down, uv = ((x + 1) / 2, (z + 1) / 2)), the point light high enough that the
// whole floor lies in its cube map's -y face.
constexpr double kQuadY = 1.0;
const glm::dvec3 kLight{0.3, 4.0, 0.2};
constexpr int kCells = 8;  // the checkerboard's texels per side

// The quad's uv is uvOffset + uvScale * its position in [0, 1]^2 (the checker scenes: 0 and 1).
Scene makeQuadScene(const AlphaMask& mask, const AlphaTexture* texture, double uvScale,
                    double uvOffset, bool alphaEffect, int width, int height) {
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {6, 0, 0}, {0, 0, -6}, 4, "floor"));
    MeshPrimitive quad;
    quad.name = "quad";
    for (const glm::dvec2 xz :
         {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)}) {
        quad.wsPositions.push_back({xz.x, kQuadY, xz.y});
        if (texture) quad.uvs.push_back(glm::vec2(uvOffset + uvScale * (xz + 1.0) * 0.5));
    }
    quad.indices = {0, 1, 2, 0, 2, 3};  // normal -y
    quad.alpha = mask;
    if (texture) {
        s.alphaTextures.push_back(*texture);
        quad.alpha->texture = 0;
    }
    s.meshes.push_back(quad);
    s.lights = {pointLight("point", kLight)};
    s.camera.wsEye = {0.5, 7.0, 4.5};
    s.camera.wsTarget = {0.0, 0.0, 0.0};
    s.camera.vfovDeg = 45.0;
    s.camera.width = width;
    s.camera.height = height;
    s.effects =
        alphaEffect ? std::vector<std::string>{"hard", "alpha"} : std::vector<std::string>{"hard"};
    finalizeScene(s);
    return s;
}

enum class Mask { Checker, ConstantBelowCutoff };

Scene makeAlphaScene(Mask mask, bool alphaEffect, int width, int height) {
    AlphaMask m;
    m.cutoff = 0.5f;
    if (mask == Mask::ConstantBelowCutoff) {
        m.factor = 0.3f;  // below the cutoff everywhere: the quad is not there
        return makeQuadScene(m, nullptr, 1.0, 0.0, alphaEffect, width, height);
    }
    AlphaTexture t{"checker", kCells, kCells, {}, {}};
    for (int y = 0; y < kCells; ++y)
        for (int x = 0; x < kCells; ++x) t.alpha.push_back((x + y) % 2 ? 0.0f : 1.0f);
    m.filter = TextureFilter::Nearest;
    m.wrapS = m.wrapT = TextureWrap::ClampToEdge;
    return makeQuadScene(m, &t, 1.0, 0.0, alphaEffect, width, height);
}

// Where the line from `from` through `to` crosses the quad's plane, as a position in the quad's
// [0, 1]^2 (its uv in the checker scenes).
glm::dvec2 quadUv(const glm::dvec3& from, const glm::dvec3& to) {
    const double t = (kQuadY - from.y) / (to.y - from.y);
    const glm::dvec3 q = from + t * (to - from);
    return {(q.x + 1.0) * 0.5, (q.z + 1.0) * 0.5};
}

// Within `band` (uv units) of a cell boundary of a quad split into `cells` per side (cells = 1:
// only its outline), where a shadow map's texels may fall either way.
bool nearBoundary(glm::dvec2 uv, int cells, double band) {
    if (uv.x < -band || uv.x > 1.0 + band || uv.y < -band || uv.y > 1.0 + band) return false;
    auto near = [&](double u) {
        return std::fabs(u * cells - std::round(u * cells)) < band * cells;
    };
    return near(uv.x) || near(uv.y);
}

// Whether the quad is there at uv: inside it, and (with the mask applied) the CPU test keeps it.
bool quadBlocks(const Scene& s, glm::dvec2 uv) {
    if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0) return false;
    if (!s.alphaTested(1)) return true;
    const AlphaMask& m = *s.meshes[1].alpha;
    return alphaKeeps(m, m.texture >= 0 ? &s.alphaTextures[size_t(m.texture)] : nullptr,
                      glm::vec2(uv));
}

struct Render {
    ChannelImage image;
    GLenum glError = GL_NO_ERROR;
};

Render raster(const Scene& scene, const std::string& technique,
              const std::vector<std::string>& settings) {
    std::string why;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    while (glGetError() != GL_NO_ERROR) {
    }
    Render r{renderRaster(scene, *createTechnique(technique, settings), o, *glContext(why)).image};
    r.glError = glGetError();
    return r;
}

glm::dvec3 position(const ChannelImage& img, size_t i) {
    return {img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]};
}

// The shadow pass: floor pixels away from the cells' boundaries, raster V > 0.5 against the CPU's.
struct ShadowCheck {
    size_t counted = 0, mismatched = 0, expectedShadow = 0, expectedHolesLit = 0;
};

ShadowCheck checkShadow(const Scene& s, const ChannelImage& img, int cells, double band) {
    ShadowCheck c;
    const float* V = img.channel(ch::lightChannel("point", ch::kVisibility));
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (img.channel(ch::kHit)[i] == 0.0f || img.channel(ch::kMeshId)[i] != 0.0f) continue;
        const glm::dvec2 uv = quadUv(position(img, i), kLight);
        if (nearBoundary(uv, cells, band)) continue;
        const bool blocked = quadBlocks(s, uv),
                   inside = uv.x > 0 && uv.x < 1 && uv.y > 0 && uv.y < 1;
        ++c.counted;
        c.expectedShadow += blocked;
        c.expectedHolesLit += inside && !blocked;
        c.mismatched += (V[i] > 0.5f) == blocked;
    }
    return c;
}

// The camera pass: a pixel that sees the quad must be where the mask keeps it; one that sees the
// floor through the quad's outline must be where the mask drops it.
struct CameraCheck {
    size_t counted = 0, mismatched = 0, quadSeen = 0, floorThroughHoles = 0;
};

CameraCheck checkCamera(const Scene& s, const ChannelImage& img, int cells, double band) {
    CameraCheck c;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (img.channel(ch::kHit)[i] == 0.0f) continue;
        const bool quad = img.channel(ch::kMeshId)[i] == 1.0f;
        const glm::dvec2 uv = quadUv(s.camera.wsEye, position(img, i));
        if (nearBoundary(uv, cells, band)) continue;
        const bool inside = uv.x > 0 && uv.x < 1 && uv.y > 0 && uv.y < 1;
        if (!inside && !quad) continue;
        ++c.counted;
        c.quadSeen += quad;
        c.floorThroughHoles += !quad;
        c.mismatched += quad != quadBlocks(s, uv);
    }
    return c;
}

constexpr double kBand = 0.01;  // uv: 0.02 world units, about 7 map texels at 2048 on the quad

// The checkerboard's holes, per pixel, in the shadow map (a cube map at 2048) and in the camera
// pass, against the CPU's mask.
void expectCheckerHoles(const std::string& technique) {
    const Scene s = makeAlphaScene(Mask::Checker, true, 256, 256);
    ASSERT_TRUE(s.alphaTested(1));
    const Render r = raster(s, technique, {"resolution=2048"});
    EXPECT_EQ(r.glError, GLenum(GL_NO_ERROR));
    const ShadowCheck sc = checkShadow(s, r.image, kCells, kBand);
    const CameraCheck cc = checkCamera(s, r.image, kCells, kBand);
    std::printf(
        "[ alpha ] %s 2048: shadow %zu of %zu floor pixels differ from the CPU mask (%zu "
        "expected in shadow, %zu lit through holes); camera %zu of %zu differ (%zu see the "
        "quad, %zu the floor through it)\n",
        technique.c_str(), sc.mismatched, sc.counted, sc.expectedShadow, sc.expectedHolesLit,
        cc.mismatched, cc.counted, cc.quadSeen, cc.floorThroughHoles);
    ASSERT_GT(sc.expectedShadow, 1000u);
    ASSERT_GT(sc.expectedHolesLit, 1000u);
    ASSERT_GT(cc.quadSeen, 1000u);
    ASSERT_GT(cc.floorThroughHoles, 1000u);
    EXPECT_LE(double(sc.mismatched) / double(sc.counted), 1e-3);
    EXPECT_LE(double(cc.mismatched) / double(cc.counted), 1e-3);
}

TEST(RasterAlpha, CheckerHolesBasic) {
    REQUIRE_GL();
    expectCheckerHoles("basic");
}

TEST(RasterAlpha, CheckerHolesPcf) {
    REQUIRE_GL();
    expectCheckerHoles("pcf");
}

TEST(RasterAlpha, ConstantAlphaBelowCutoffIsNotThere) {
    REQUIRE_GL();
    const Scene s = makeAlphaScene(Mask::ConstantBelowCutoff, true, 160, 160);
    ASSERT_TRUE(s.alphaTested(1));
    const Render r = raster(s, "basic", {"resolution=1024"});
    EXPECT_EQ(r.glError, GLenum(GL_NO_ERROR));
    size_t quadPixels = 0, floorPixels = 0, shadowed = 0;
    const float* V = r.image.channel(ch::lightChannel("point", ch::kVisibility));
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (r.image.channel(ch::kHit)[i] == 0.0f) continue;
        quadPixels += r.image.channel(ch::kMeshId)[i] == 1.0f;
        floorPixels += r.image.channel(ch::kMeshId)[i] == 0.0f;
        shadowed += V[i] <= 0.5f;
    }
    std::printf(
        "[ alpha ] factor 0.3 < cutoff 0.5: %zu quad pixels, %zu of %zu floor pixels "
        "shadowed\n",
        quadPixels, shadowed, floorPixels);
    EXPECT_EQ(quadPixels, 0u);
    EXPECT_GT(floorPixels, 10000u);
    EXPECT_EQ(shadowed, 0u);
}

TEST(RasterAlpha, WithoutTheAlphaEffectTheMaskIsIgnored) {
    REQUIRE_GL();
    const Scene s = makeAlphaScene(Mask::Checker, false, 160, 160);
    ASSERT_FALSE(s.alphaTested(1));
    const Render r = raster(s, "basic", {"resolution=2048"});
    EXPECT_EQ(r.glError, GLenum(GL_NO_ERROR));
    const ShadowCheck sc = checkShadow(s, r.image, 1, kBand);
    const CameraCheck cc = checkCamera(s, r.image, 1, kBand);
    std::printf(
        "[ alpha ] no \"alpha\" effect: shadow %zu of %zu differ (%zu expected in shadow, "
        "%zu through holes); camera %zu of %zu differ (%zu see the floor through it)\n",
        sc.mismatched, sc.counted, sc.expectedShadow, sc.expectedHolesLit, cc.mismatched,
        cc.counted, cc.floorThroughHoles);
    ASSERT_GT(sc.expectedShadow, 1000u);
    EXPECT_EQ(sc.expectedHolesLit, 0u);
    EXPECT_EQ(cc.floorThroughHoles, 0u);
    EXPECT_LE(double(sc.mismatched) / double(sc.counted), 1e-3);
    EXPECT_EQ(cc.mismatched, 0u);
}

// Wrap modes and both filters, in the camera pass: the quad's uv runs from -0.75 to 1.75 over a
// 5 x 3 texture of scattered alphas, so every wrap mode is exercised beyond [0, 1]. A pixel that
// sees the quad must be where the CPU keeps it, one that sees the floor through its outline where
// the CPU drops it, except, for GL_LINEAR, where the CPU's alpha is within 0.01 of the cutoff (its
// weights have the implementation's precision, not the CPU's float), and for GL_NEAREST where the
// uv is within 1e-3 texels of a texel edge (the choice there rests on the uv's last bits).
TEST(RasterAlpha, WrapModesAndFiltersMatchTheCpu) {
    REQUIRE_GL();
    // GL_LINEAR's weights may have as few as 8 bits (GPUs commonly), which moves a bilinear
    // alpha by up to 2 x 0.9 / 256 (two axes, the largest texel difference times the factor).
    const float kBilinearBand = 0.01f;
    AlphaTexture t{"scattered", 5, 3, {}, {}};
    for (int i = 0; i < 15; ++i) t.alpha.push_back(float((i * 7) % 15) / 14.0f);
    const TextureWrap kWraps[3][2] = {{TextureWrap::Repeat, TextureWrap::MirroredRepeat},
                                      {TextureWrap::ClampToEdge, TextureWrap::Repeat},
                                      {TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge}};
    for (const TextureFilter filter : {TextureFilter::Nearest, TextureFilter::Bilinear})
        for (const auto& wrap : kWraps) {
            AlphaMask m;
            m.cutoff = 0.45f;
            m.factor = 0.9f;
            m.filter = filter;
            m.wrapS = wrap[0];
            m.wrapT = wrap[1];
            const Scene s = makeQuadScene(m, &t, 2.5, -0.75, true, 160, 160);
            const Render r = raster(s, "basic", {"resolution=64"});
            EXPECT_EQ(r.glError, GLenum(GL_NO_ERROR));
            size_t counted = 0, mismatched = 0, skipped = 0, quadSeen = 0;
            for (size_t i = 0; i < r.image.pixelCount(); ++i) {
                if (r.image.channel(ch::kHit)[i] == 0.0f) continue;
                const bool quad = r.image.channel(ch::kMeshId)[i] == 1.0f;
                const glm::dvec2 at = quadUv(s.camera.wsEye, position(r.image, i));
                if (!quad && !(at.x > 0 && at.x < 1 && at.y > 0 && at.y < 1)) continue;
                const glm::vec2 uv(-0.75 + 2.5 * at);
                const glm::vec2 texel = uv * glm::vec2(5.0f, 3.0f);
                const float a = sampleAlpha(m, &t, uv);
                if ((filter == TextureFilter::Bilinear &&
                     std::fabs(a - m.cutoff) < kBilinearBand) ||
                    nearBoundary(at, 1, 1e-3) ||
                    (filter == TextureFilter::Nearest &&
                     (std::fabs(texel.x - std::round(texel.x)) < 1e-3f ||
                      std::fabs(texel.y - std::round(texel.y)) < 1e-3f))) {
                    ++skipped;
                    continue;
                }
                ++counted;
                quadSeen += quad;
                mismatched += quad != alphaKeeps(m, &t, uv);
            }
            std::printf(
                "[ alpha ] %s, wrap %d/%d: camera %zu of %zu pixels differ from the CPU "
                "(%zu see the quad, %zu skipped near the cutoff or an edge)\n",
                filter == TextureFilter::Nearest ? "nearest" : "bilinear", int(wrap[0]),
                int(wrap[1]), mismatched, counted, quadSeen, skipped);
            EXPECT_GT(quadSeen, 500u);
            EXPECT_GT(counted - quadSeen, 500u);
            EXPECT_LE(double(mismatched) / double(counted), 1e-3);
        }
}

// z-pass counts volume faces between the eye and the surface and relies on the caster to hide
// the entry through its own cap: through the caster's holes the camera sees the receiver, the
// entry is missed, and the count comes out inverted (docs/techniques.md, "Alpha-tested
// occluders"). Per floor pixel, with the caster opaque in the volume: seen through the quad's
// outline, V = 1 inside its shadow and 0 outside; elsewhere V = 0 inside its shadow.
TEST(RasterAlpha, VolumeZPassInvertsWhatIsSeenThroughHoles) {
    REQUIRE_GL();
    const Scene s = makeAlphaScene(Mask::Checker, true, 192, 192);
    const Render r = raster(s, "volume-zpass", {});
    EXPECT_EQ(r.glError, GLenum(GL_NO_ERROR));
    const float* V = r.image.channel(ch::lightChannel("point", ch::kVisibility));
    size_t counted = 0, mismatched = 0, throughHoles = 0;
    auto inside = [](glm::dvec2 uv) { return uv.x > 0 && uv.x < 1 && uv.y > 0 && uv.y < 1; };
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (r.image.channel(ch::kHit)[i] == 0.0f || r.image.channel(ch::kMeshId)[i] != 0.0f)
            continue;
        const glm::dvec3 p = position(r.image, i);
        const glm::dvec2 fromLight = quadUv(p, kLight), fromEye = quadUv(s.camera.wsEye, p);
        if (nearBoundary(fromLight, 1, kBand) || nearBoundary(fromEye, 1, kBand)) continue;
        const bool seenThrough = inside(fromEye), inShadow = inside(fromLight);
        ++counted;
        throughHoles += seenThrough;
        mismatched += (V[i] > 0.5f) != (seenThrough == inShadow);
    }
    std::printf(
        "[ alpha ] volume-zpass: %zu of %zu floor pixels differ from the inverted count "
        "(%zu seen through holes)\n",
        mismatched, counted, throughHoles);
    ASSERT_GT(throughHoles, 500u);
    EXPECT_LE(double(mismatched) / double(counted), 1e-3);
}

// What docs/techniques.md ("Alpha-tested occluders") says per technique: volume-zfail, and
// accumulate over it (its default method), draw a masked caster opaque; volume-zpass gets the
// pixels seen through holes wrong (the test above); every other technique cuts the holes.
std::vector<std::string> techniqueNames() {
    std::vector<std::string> names;
    for (const TechniqueInfo* t : allTechniques()) names.push_back(t->name);
    return names;
}

class RasterAlphaTechnique : public testing::TestWithParam<std::string> {};

// Mean V over the floor inside the quad's shadow, away from its outline: the share of the
// checkerboard's holes (half of it) a technique lets light through; 0 for an opaque caster.
double meanVInShadow(const Scene& s, const std::string& technique,
                     std::vector<std::string> settings) {
    const std::string label = technique + (settings.empty() ? "" : " " + settings.front());
    for (const ParamSpec& p : findTechnique(technique).params)
        if (p.name == "resolution") settings.push_back("resolution=512");
    const Render r = raster(s, technique, settings);
    EXPECT_EQ(r.glError, GLenum(GL_NO_ERROR)) << technique;
    const float* V = r.image.channel(ch::lightChannel("point", ch::kVisibility));
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (r.image.channel(ch::kHit)[i] == 0.0f || r.image.channel(ch::kMeshId)[i] != 0.0f)
            continue;
        const glm::dvec2 uv = quadUv(position(r.image, i), kLight);
        if (nearBoundary(uv, 1, 0.05) || uv.x < 0 || uv.x > 1 || uv.y < 0 || uv.y > 1) continue;
        sum += V[i];
        ++n;
    }
    EXPECT_GT(n, 500u) << technique;
    const double meanV = n ? sum / double(n) : 0.0;
    std::printf("[ alpha ] %s: mean V in the quad's shadow %.3f over %zu pixels\n", label.c_str(),
                meanV, n);
    return meanV;
}

TEST_P(RasterAlphaTechnique, RendersTheMaskOrDocumentsItOpaque) {
    REQUIRE_GL();
    const std::string name = GetParam();
    const Scene s = makeAlphaScene(Mask::Checker, true, 128, 128);
    const double meanV = meanVInShadow(s, name, {});
    if (name == "volume-zpass") return;  // neither: VolumeZPassInvertsWhatIsSeenThroughHoles
    if (name == "volume-zfail" || name == "accumulate")
        EXPECT_LT(meanV, 0.02);
    else
        EXPECT_GT(meanV, 0.3);
    if (name == "accumulate") {
        EXPECT_GT(meanVInShadow(s, name, {"method=0"}), 0.3);
    }
}

INSTANTIATE_TEST_SUITE_P(All, RasterAlphaTechnique, testing::ValuesIn(techniqueNames()),
                         [](const testing::TestParamInfo<std::string>& param) {
                             std::string id = param.param;
                             for (char& c : id)
                                 if (c == '-') c = '_';
                             return id;
                         });

}  // namespace
}  // namespace so::test
