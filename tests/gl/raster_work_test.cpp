// The work counts of the raster path (docs/metrics.md, "Work"): exact on cases whose counts are
// known in closed form. Label "gl"; skipped with the reason where no EGL display opens.
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "gl_test_context.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"
#include "test_scenes.h"

namespace so::test {
namespace {

const RasterLightStats& light(const RasterResult& r, const std::string& name) {
    for (const RasterLightStats& l : r.stats.lights)
        if (l.name == name) return l;
    throw std::runtime_error("no light " + name);
}

const PassWork& pass(const RasterResult& r, const std::string& lightName, const std::string& p) {
    return light(r, lightName).workByPass.at(p);
}

// The pixels where the camera sees a surface.
uint64_t visiblePixels(const ChannelImage& image) {
    uint64_t n = 0;
    const float* hit = image.channel(channels::kHit);
    for (size_t i = 0; i < image.pixelCount(); ++i) n += hit[i] != 0.0f;
    return n;
}

bool llvmpipe(const RasterResult& r) {
    return r.stats.gl.renderer.rfind("llvmpipe", 0) == 0;
}

// A full-screen pass shades every pixel once: blur's two passes (across, then down) at an odd
// size, 2 W H fragments and 2 W H texels (its second pass leaves the aliasing target alone).
TEST(Work, FullScreenPassShadesWidthTimesHeightFragments) {
    REQUIRE_GL();
    const int w = 37, h = 23;
    const RasterResult r =
        renderOneFrame(makeSquareOccluderScene(w, h).scene, "blur", {"radius=2", "resolution=256"});
    const PassWork& blur = pass(r, "sun", "blur");
    EXPECT_EQ(blur.counts.fragments, uint64_t(2 * w * h));
    EXPECT_EQ(blur.counts.texelsWritten, uint64_t(2 * w * h));
    EXPECT_EQ(blur.counts.drawCalls, 2u);
    EXPECT_EQ(blur.counts.passes, 1u);
    // What the driver's own counter says: llvmpipe runs the shader on whole 4 x 4 blocks and
    // counts 16 to each block a triangle touches, after clipping (its clipper splits the
    // full-screen triangle, and blocks along the cut count twice): more than W H, at least every
    // block of the viewport.
    ASSERT_TRUE(blur.pipeline.has_value());
    if (llvmpipe(r)) {
        const uint64_t invocations = blur.pipeline->fragmentShaderInvocations;
        EXPECT_EQ(invocations % 16, 0u);
        EXPECT_GE(invocations, uint64_t(2 * 16 * ((w + 3) / 4) * ((h + 3) / 4)));
        std::printf(
            "[ work ] llvmpipe's fragment shader invocations of two full-screen passes "
            "at %d x %d: %llu (%d fragments)\n",
            w, h, (unsigned long long)invocations, 2 * w * h);
    }
    EXPECT_EQ(blur.pipeline->verticesSubmitted, 6u);
    EXPECT_EQ(blur.pipeline->primitivesSubmitted, 2u);
}

// A 1024^2 depth map pass writes 1,048,576 texels (a cube map six times that), 4 bytes each in
// 24-bit depth, 2 in 16-bit; with one draw per mesh and face.
TEST(Work, DepthMapPassWritesItsTexels) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(64, 48).scene;
    for (int bits : {24, 16}) {
        const RasterResult r =
            renderOneFrame(s, "basic", {"resolution=1024", "depth_format=" + std::to_string(bits)});
        const uint64_t texelBytes = bits == 16 ? 2 : 4;
        for (const char* l : {"sun", "spot", "point"}) {
            const uint64_t faces = std::string(l) == "point" ? 6 : 1;
            const PassWork& map = pass(r, l, "shadow_map");
            EXPECT_EQ(map.counts.texelsWritten, faces * 1048576u) << l;
            EXPECT_EQ(map.targetBytesWritten, faces * 1048576u * texelBytes) << l;
            EXPECT_EQ(map.counts.drawCalls, faces * s.meshes.size()) << l;
            EXPECT_EQ(map.counts.textureTaps, 0u) << l;
        }
    }
}

// pcf with kernel 5 takes 25 taps per lit receiver fragment, hw-pcf one (of 2 x 2 texels). Every
// surface the camera sees here faces the sun and the point light and lies inside their maps, so
// every visibility fragment is a lit receiver: one per visible pixel.
TEST(Work, PcfTakesKernelSquaredTapsPerLitReceiverFragment) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(96, 72).scene;
    const RasterResult pcf = renderOneFrame(s, "pcf", {"kernel=5", "resolution=512"});
    const RasterResult hw = renderOneFrame(s, "hw-pcf", {"resolution=512"});
    const uint64_t pixels = visiblePixels(pcf.image);
    ASSERT_GT(pixels, 1000u);
    for (const char* l : {"sun", "point"}) {
        const PassWork& p = pass(pcf, l, "visibility");
        EXPECT_EQ(p.counts.fragments, pixels) << l;
        EXPECT_EQ(p.counts.textureTaps, 25 * pixels) << l;
        EXPECT_EQ(p.tapBytes, 25 * pixels * 4) << l;  // one 24-bit depth texel each
        const PassWork& h = pass(hw, l, "visibility");
        EXPECT_EQ(h.counts.textureTaps, pixels) << l;
        EXPECT_EQ(h.tapBytes, pixels * 4 * 4) << l;
    }
    // The spot's cone leaves part of the view unlit: no taps there, 25 per fragment inside.
    const PassWork& spot = pass(pcf, "spot", "visibility");
    EXPECT_EQ(spot.counts.fragments, pixels);
    EXPECT_LT(spot.counts.textureTaps, 25 * pixels);
    EXPECT_GT(spot.counts.textureTaps, 0u);
    EXPECT_EQ(spot.counts.textureTaps % 25, 0u);
}

// An invocation's taps count though it discards after them: accumulate's weight pass reads every
// pixel's position and discards the background; on a surface it reads the normal and the sample's
// V too. The sun is its own single sample; the resolve reads the sums once a pixel.
TEST(Work, TapsBeforeADiscardCount) {
    REQUIRE_GL();
    const int w = 64, h = 48;
    const RasterResult r = renderOneFrame(makeSquareOccluderScene(w, h).scene, "accumulate",
                                          {"samples=4", "method=volume"});
    const uint64_t hit = visiblePixels(r.image);
    ASSERT_GT(hit, 100u);
    ASSERT_LT(hit, uint64_t(w * h)) << "the test needs background pixels";
    const PassWork& acc = pass(r, "sun", "accumulate");
    EXPECT_EQ(acc.counts.textureTaps, uint64_t(2 * w * h) + 2 * hit);
    EXPECT_EQ(acc.counts.fragments, uint64_t(2 * w * h));
    EXPECT_EQ(acc.counts.passes, 2u);
}

// A shadow volume pass's fragments are its occlusion query's: the fragments that pass the depth
// test, which z-pass's stencil counts (the fill) and z-fail's leaves (it counts those behind).
TEST(Work, ShadowVolumeFillEqualsItsOcclusionQuery) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(96, 72).scene;
    for (const char* technique : {"volume-zpass", "volume-zfail"}) {
        const RasterResult r = renderOneFrame(s, technique, {});
        for (const RasterLightStats& l : r.stats.lights) {
            const int64_t fill = l.counts.at("volume_fill_px"),
                          all = l.counts.at("volume_fragments");
            ASSERT_GT(fill, 0) << technique << " " << l.name;
            const uint64_t expected =
                uint64_t(std::string(technique) == "volume-zpass" ? fill : all - fill);
            EXPECT_EQ(l.workByPass.at("volumes").counts.fragments, expected)
                << technique << " " << l.name;
            EXPECT_EQ(l.workByPass.at("volumes").counts.textureTaps, 0u);
        }
    }
}

// A light's volume counts are its own: the stencil state an earlier light's visibility pass
// leaves (GL_EQUAL over its count) once hid fragments from the queries of the next.
TEST(Work, VolumeCountsDoNotDependOnTheLightsBefore) {
    REQUIRE_GL();
    const Scene all = makeSquareOccluderScene(96, 72).scene;
    for (size_t k = 1; k < all.lights.size(); ++k) {
        Scene alone = all;
        alone.lights = {all.lights[k]};
        finalizeScene(alone);
        const RasterResult a = renderOneFrame(all, "volume-zfail", {}, false),
                           b = renderOneFrame(alone, "volume-zfail", {}, false);
        const std::string& name = all.lights[k].name;
        EXPECT_EQ(light(a, name).counts, light(b, name).counts) << name;
    }
}

// The light's work is the sum of its passes, the frame's the lights' and the camera pass's; every
// mesh is one draw in the camera and visibility passes.
TEST(Work, LightsAndFrameAreSumsOfTheirPasses) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(64, 48).scene;
    const RasterResult r = renderOneFrame(s, "vsm", {"resolution=256"});
    ASSERT_TRUE(r.stats.frameWork && r.stats.cameraWork);
    WorkCounts frame = r.stats.cameraWork->counts;
    for (const RasterLightStats& l : r.stats.lights) {
        ASSERT_TRUE(l.work.has_value());
        WorkCounts sum;
        for (const auto& [name, w] : l.workByPass) sum += w.counts;
        EXPECT_EQ(sum, l.work->counts) << l.name;
        EXPECT_EQ(l.work->counts.passes, 2u);
        EXPECT_EQ(l.workByPass.at("visibility").counts.drawCalls, s.meshes.size());
        EXPECT_EQ(l.work->counts.bytesMoved,
                  l.work->tapBytes + l.work->targetBytesRead + l.work->targetBytesWritten);
        frame += l.work->counts;
    }
    EXPECT_EQ(frame, r.stats.frameWork->counts);
    EXPECT_EQ(r.stats.cameraWork->counts.drawCalls, s.meshes.size());
    // The moment map's blur (blur 2: 5 taps a texel), a cube map's across its faces: per face one
    // tap for each texel of the face padded by 2, then along s over the face and 2 rows beyond
    // either side, then along t over the face.
    const PassWork& point = pass(r, "point", "shadow_map");
    EXPECT_EQ(point.counts.textureTaps, uint64_t(6 * (260 * 260 + 5 * 256 * (260 + 256))));
    const PassWork& spot = pass(r, "spot", "shadow_map");
    EXPECT_EQ(spot.counts.textureTaps, uint64_t(2 * 5 * 256 * 256));
}

// The counted frame is a build of its own: the timed frames, and so the image, are those of a
// render that counts nothing.
TEST(Work, CountingLeavesTheImageAlone) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(64, 48).scene;
    for (const char* technique : {"pcf", "vsm", "volume-zfail", "blur", "pcss"}) {
        const std::vector<std::string> settings = std::string(technique) == "volume-zfail"
                                                      ? std::vector<std::string>{}
                                                      : std::vector<std::string>{"resolution=512"};
        const RasterResult counted = renderOneFrame(s, technique, settings, true),
                           uncounted = renderOneFrame(s, technique, settings, false);
        EXPECT_FALSE(uncounted.stats.frameWork.has_value());
        for (const Light& l : s.lights) {
            const std::string v = channels::lightChannel(l.name, channels::kVisibility);
            const float *a = counted.image.channel(v), *b = uncounted.image.channel(v);
            size_t differ = 0;
            for (size_t i = 0; i < counted.image.pixelCount(); ++i) differ += a[i] != b[i];
            EXPECT_EQ(differ, 0u) << technique << " " << l.name;
        }
    }
}

// Every technique counts its work: its passes draw, its visibility pass shades the lit pixels,
// and a technique that reads a map or a target takes taps.
TEST(Work, EveryTechniqueIsCounted) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(48, 36).scene;
    for (const TechniqueInfo* t : allTechniques()) {
        std::vector<std::string> settings;
        for (const ParamSpec& p : t->params)
            if (p.name == "resolution") settings.push_back("resolution=256");
        const RasterResult r = renderOneFrame(s, t->name, settings);
        const PassWork& sun = *light(r, "sun").work;
        EXPECT_GT(sun.counts.drawCalls, 0u) << t->name;
        EXPECT_GT(sun.counts.fragments, 0u) << t->name;
        EXPECT_GT(sun.counts.texelsWritten, 0u) << t->name;
        EXPECT_GE(sun.counts.passes, light(r, "sun").passes.size()) << t->name;
        const bool readsTextures = t->family != "shadow volume" && t->family != "planar projection";
        if (readsTextures) {
            EXPECT_GT(sun.counts.textureTaps, 0u) << t->name;
        } else {
            EXPECT_EQ(sun.counts.textureTaps, 0u) << t->name;
        }
    }
}

}  // namespace
}  // namespace so::test
