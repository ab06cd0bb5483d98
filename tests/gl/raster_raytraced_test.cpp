// The raytraced family (issue 53): shadow rays from the raster path's G-buffer, traced by Embree,
// and their denoisers. One ray at a point light is the exact hard shadow (the plumbing against the
// oracle); on a rect light over a parallel occluder (lambert.h's closed-form scene) 16 still
// frames of svgf converge where the raw rays stay noisy; rays are counted as work; the rays are
// the same at any thread count. Label "gl" (the tracer's own test needs no GL).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "core/error.h"
#include "core/scene.h"
#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/gl/rays/shadow_rays.h"
#include "raster_compare/gl/time/temporal_state.h"
#include "test_scenes.h"

namespace so::test {
namespace {

// Frames 0 .. frames - 1 of one technique object, as a sequence renders them: its history carries
// from each frame to the next. The last frame's image.
ChannelImage lastOfStillFrames(const Scene& s, const std::string& technique,
                               const std::vector<std::string>& settings, int frames) {
    std::string why;
    const std::unique_ptr<Technique> t = createTechnique(technique, settings);
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    o.countWork = false;
    TemporalState state;  // the caller's: what each frame leaves for the next
    o.temporal = &state;
    ChannelImage last;
    for (int f = 0; f < frames; ++f) {
        state.beginFrame(f);
        o.frameIndex = f;
        last = renderRaster(s, *t, o, *glContext(why)).image;
    }
    return last;
}

// A point light over a square tilted 20 degrees, 1 above a floor: a hard shadow with slanted
// edges across the pixel grid.
TEST(Raytraced, OneRayAtAPointLightIsTheOraclesHardShadow) {
    REQUIRE_GL();
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {12, 0, 0}, {0, 0, -12}, 4, "floor"));
    const double a = 20.0 * 3.14159265358979 / 180.0;
    s.meshes.push_back(
        makeGrid({0.2, 1.0, 0.1}, {2 * std::cos(a), 2 * std::sin(a), 0}, {0, 0, -2}, 1, "square"));
    Light point;
    point.name = "lamp";
    point.type = LightType::Point;
    point.wsPosition = {0.5, 4.0, 0.5};
    s.lights = {point};
    s.effects = {"hard"};
    aimCamera(s, {0.0, 6.0, 5.0}, {0.0, 0.0, 0.0}, 40, 64, 64);
    finalizeScene(s);
    const ChannelImage oracle = runQuiet(s);
    const ChannelImage rt = renderOneFrame(s, "raytraced", {"spp=1", "denoiser=none"}, false).image;
    const LightMetrics m = computeLightMetrics(oracle, rt, "lamp", {});
    std::printf("[ raytraced ] point light over a tilted square: mae %.5f\n", m.mae);
    EXPECT_LE(m.mae, 0.002);
}

// lambert.h's rect light over a parallel square: 16 still frames. The raw single ray stays a coin
// flip per pixel in the penumbra; svgf's temporal moments and a-trous converge towards the exact
// penumbra, past pcss's approximation.
TEST(Raytraced, SvgfConvergesOnStillFrames) {
    REQUIRE_GL();
    const PenumbraScene p = makePenumbraScene(64, 64);
    const ChannelImage oracle = runQuiet(p.scene);
    const auto penumbraMae = [&](const ChannelImage& image) {
        const LightMetrics m = computeLightMetrics(oracle, image, "panel", {});
        EXPECT_TRUE(m.penumbraMae.has_value());
        return m.penumbraMae.value_or(1.0);
    };
    const double none =
        penumbraMae(lastOfStillFrames(p.scene, "raytraced", {"spp=1", "denoiser=none"}, 16));
    const double svgf =
        penumbraMae(lastOfStillFrames(p.scene, "raytraced", {"spp=1", "denoiser=svgf"}, 16));
    const double temporal =
        penumbraMae(lastOfStillFrames(p.scene, "raytraced", {"spp=1", "denoiser=temporal"}, 16));
    const double ffx =
        penumbraMae(lastOfStillFrames(p.scene, "raytraced", {"spp=1", "denoiser=ffx"}, 16));
    const double hitdist =
        penumbraMae(lastOfStillFrames(p.scene, "raytraced", {"spp=1", "denoiser=hitdist"}, 16));
    const double pcss = penumbraMae(renderOneFrame(p.scene, "pcss", {}, false).image);
    std::printf(
        "[ raytraced ] 16 still frames, penumbra mae: none %.4f, temporal %.4f, svgf %.4f, "
        "ffx %.4f, hitdist %.4f; pcss %.4f\n",
        none, temporal, svgf, ffx, hitdist, pcss);
    EXPECT_GT(none, 2.0 * svgf);
    EXPECT_LT(svgf, pcss);
    EXPECT_LT(temporal, none);
    EXPECT_LT(ffx, 0.5 * none);
    EXPECT_LT(hitdist, temporal);  // the spatial filter removes what the history left
}

// Every pixel that sees the light's side traces spp rays: at least the lit pixels times spp, at
// most all the pixels times spp.
TEST(Raytraced, CountsItsRays) {
    REQUIRE_GL();
    const PenumbraScene p = makePenumbraScene(48, 48);
    const int spp = 2;
    const RasterResult r = renderOneFrame(p.scene, "raytraced", {"spp=2"}, true);
    ASSERT_EQ(r.stats.lights.size(), 1u);
    ASSERT_TRUE(r.stats.lights[0].work.has_value());
    const uint64_t rays = r.stats.lights[0].work->counts.raysTraced;
    const float* v = r.image.channel(channels::lightChannel("panel", channels::kVisibility));
    uint64_t lit = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) lit += v[i] > 0.0f ? 1 : 0;
    std::printf("[ raytraced ] %llu rays, %llu lit pixels at spp %d\n", (unsigned long long)rays,
                (unsigned long long)lit, spp);
    EXPECT_GT(lit, 0u);
    EXPECT_GE(rays, lit * uint64_t(spp));
    EXPECT_LE(rays, uint64_t(r.image.pixelCount()) * uint64_t(spp));
}

// Frames 0 .. 3 of `settings` on the penumbra scene, the camera moving a little each frame (so
// every history is reprojected): the last frame's V of the light, with its work counted.
RasterResult lastOfMovingFrames(const std::vector<std::string>& settings) {
    PenumbraScene p = makePenumbraScene(40, 32);
    std::string why;
    const std::unique_ptr<Technique> t = createTechnique("raytraced", settings);
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    TemporalState state;
    o.temporal = &state;
    RasterResult last;
    for (int f = 0; f < 4; ++f) {
        aimCamera(p.scene, {0.25 + 0.04 * f, 6.0, 5.0 - 0.03 * f}, {0.25, 0.0, 0.0}, 36, 40, 32);
        state.beginFrame(f);  // the camera alone moves
        o.frameIndex = f;
        o.countWork = f == 3;
        last = renderRaster(p.scene, *t, o, *glContext(why));
    }
    return last;
}

// The bits of the light's V (FNV-1a), for comparing one build's images with another's.
uint64_t hashOfV(const ChannelImage& image) {
    const float* v = image.channel(channels::lightChannel("panel", channels::kVisibility));
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        uint32_t bits = 0;
        std::memcpy(&bits, &v[i], 4);
        for (int b = 0; b < 4; ++b) h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
    }
    return h;
}

// The mean V of the image's four quadrants (top left, top right, bottom left, bottom right) and the
// mean of V squared: a fingerprint that any change of a denoiser's arithmetic moves.
std::vector<double> fingerprintOfV(const ChannelImage& image) {
    const float* v = image.channel(channels::lightChannel("panel", channels::kVisibility));
    const int w = image.width(), h = image.height();
    std::vector<double> f(5, 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double value = v[size_t(y) * size_t(w) + size_t(x)];
            f[size_t((y >= h / 2 ? 2 : 0) + (x >= w / 2 ? 1 : 0))] += value / (w * h / 4.0);
            f[4] += value * value / (w * h);
        }
    return f;
}

// Every denoiser's image after four moving frames, against the values it gave on Mesa's llvmpipe
// when the denoisers became plug-ins (issue 62), with its taps: moving a denoiser into its own
// file moved no number (the bits printed were the same before and after). Re-recorded in issue
// 63: ffx as AMD ships it and svgf with Falcor's fallbacks give new images; temporal and hitdist
// the same ones with one more tap a pixel (the history's length read from the nearest texel, as
// Falcor reads it). Issue 64: the same images, with one more tap a pixel for each reprojection
// (the pixel's mesh id, whose motion it follows; ffx reprojects twice). Held to 1e-6 (the values
// are printed to 9 digits). Another driver rounds its own way, and one rounding may flip a
// reprojection's or an edge stop's test at a pixel (a quadrant's mean moves 3e-4 per pixel changed
// by 0.1): there the values are printed, not held.
TEST(Raytraced, EveryDenoiserGivesItsRecordedImage) {
    REQUIRE_GL();
    const bool recordingDriver = gl->renderer().find("llvmpipe") != std::string::npos;
    struct Case {
        std::vector<std::string> settings;
        std::vector<double> fingerprint;
        uint64_t taps;
    };
    const std::vector<Case> cases = {
        {{"denoiser=none"},
         {0.868750000, 0.962500000, 0.643750000, 0.846875000, 0.830468750},
         1280},
        {{"denoiser=temporal"},
         {0.874955719, 0.959955969, 0.631016345, 0.821140242, 0.780140404},
         17682},
        {{"denoiser=svgf"},
         {0.883104912, 0.966622514, 0.651539843, 0.845223391, 0.767555840},
         393790},
        {{"denoiser=ffx"},
         {0.865657636, 0.957312779, 0.625150565, 0.827772890, 0.758162221},
         454033},
        {{"denoiser=hitdist"},
         {0.873691249, 0.959674703, 0.634340138, 0.822412965, 0.776755463},
         150325},
        // Recorded with alpha=0.3 and alpha=0.5, the new frame's weight: history = 1 - alpha.
        {{"denoiser=svgf", "spp=2", "history=0.7", "levels=3", "sigma_depth=2"},
         {0.883059269, 0.961259222, 0.667637604, 0.843470820, 0.768715905},
         299710},
        {{"denoiser=hitdist", "history=0.5", "taps=8", "search_radius=4", "max_radius=8"},
         {0.874922190, 0.959324844, 0.636046256, 0.828769046, 0.780928079},
         58499},
        {{"denoiser=ffx", "depth_similarity_sigma=0.05"},
         {0.866855662, 0.957747239, 0.632500097, 0.832513584, 0.762316681},
         454033},
    };
    for (const Case& c : cases) {
        const RasterResult r = lastOfMovingFrames(c.settings);
        const std::vector<double> f = fingerprintOfV(r.image);
        const uint64_t taps = r.stats.lights.at(0).work.value().counts.textureTaps;
        std::string label;
        for (const std::string& s : c.settings) label += s + " ";
        std::printf("[ raytraced ] %s: {%.9f, %.9f, %.9f, %.9f, %.9f}, taps %llu, bits %016llx\n",
                    label.c_str(), f[0], f[1], f[2], f[3], f[4], (unsigned long long)taps,
                    (unsigned long long)hashOfV(r.image));
        if (!recordingDriver) continue;
        for (size_t i = 0; i < f.size(); ++i) EXPECT_NEAR(f[i], c.fingerprint[i], 1e-6) << label;
        EXPECT_EQ(taps, c.taps) << label;
    }
}

// A denoiser's parameter without its denoiser is an error, not silently ignored; one shared by
// several denoisers ("key=a|b") is taken with any of them.
TEST(Raytraced, ParametersNeedTheirDenoiser) {
    EXPECT_THROW(createTechnique("raytraced", {"history=0.7"}), InputError);
    EXPECT_THROW(createTechnique("raytraced", {"denoiser=temporal", "sigma_depth=2"}), InputError);
    EXPECT_THROW(createTechnique("raytraced", {"denoiser=ffx", "levels=3"}), InputError);
    EXPECT_NO_THROW(createTechnique("raytraced", {"denoiser=svgf", "history=0.7", "levels=3"}));
    EXPECT_THROW(createTechnique("raytraced", {"denoiser=ffx", "sigma_depth=2"}), InputError);
    EXPECT_NO_THROW(createTechnique("raytraced", {"denoiser=ffx", "depth_similarity_sigma=2"}));
    EXPECT_NO_THROW(createTechnique("raytraced", {"denoiser=hitdist", "history=0.5", "taps=8"}));
}

// The former spelling renders the same bits as the new one: alpha=0.3 is history=0.7
// (tests/gl/denoiser_registry_test.cpp holds its notice).
TEST(Raytraced, FormerAlphaRendersAsHistory) {
    REQUIRE_GL();
    const RasterResult old = lastOfMovingFrames({"denoiser=temporal", "alpha=0.3"});
    const RasterResult now = lastOfMovingFrames({"denoiser=temporal", "history=0.7"});
    EXPECT_EQ(hashOfV(old.image), hashOfV(now.image));
    EXPECT_NE(hashOfV(now.image), hashOfV(lastOfMovingFrames({"denoiser=temporal"}).image));
}

// The tracer alone, on a G-buffer made in memory (the floor's points under the occluder): the same
// bits at 1 and 2 threads, another frame index another sample pattern, and the mean over frames
// near the closed form.
TEST(ShadowRays, SameAtAnyThreadCountAndAdvancesWithTheFrame) {
    const PenumbraScene p = makePenumbraScene(8, 8);
    const LocalFrame frame = LocalFrame::fit(p.scene.wsBounds);
    const int W = 24, H = 16;
    std::vector<float> position(4 * W * H), normal(4 * W * H);
    std::vector<glm::dvec3> wsPoints;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::dvec3 ws(-2.0 + 4.0 * (x + 0.5) / W, 0.0, -1.5 + 3.0 * (y + 0.5) / H);
            const glm::dvec3 ls = frame.lsFromWs(ws);
            const size_t i = size_t(y * W + x);
            for (int c = 0; c < 3; ++c) position[4 * i + c] = float(ls[c]);
            position[4 * i + 3] = 1.0f;
            normal[4 * i + 1] = 1.0f;
            wsPoints.push_back(ws);
        }
    const ShadowRayTracer tracer(p.scene, frame);
    ShadowRaySettings one{4, 3, false, 1}, two{4, 3, false, 2};
    const ShadowRayGBuffer g{W, H, position.data(), normal.data()};
    const ShadowRayFrame a = tracer.trace(g, p.scene.lights[0], one);
    EXPECT_EQ(a.visibilityAndHit, tracer.trace(g, p.scene.lights[0], two).visibilityAndHit);
    EXPECT_EQ(a.raysTraced, uint64_t(4 * W * H));
    ShadowRaySettings later = one;
    later.frameIndex = 4;
    EXPECT_NE(a.visibilityAndHit, tracer.trace(g, p.scene.lights[0], later).visibilityAndHit);
    // 64 frames of 4 rays: 256 points of one Sobol sequence per pixel.
    std::vector<double> mean(size_t(W * H), 0.0);
    for (int f = 0; f < 64; ++f) {
        ShadowRaySettings s = one;
        s.frameIndex = f;
        const ShadowRayFrame r = tracer.trace(g, p.scene.lights[0], s);
        for (size_t i = 0; i < mean.size(); ++i) mean[i] += r.visibilityAndHit[2 * i] / 64.0;
    }
    double err = 0.0;
    for (size_t i = 0; i < mean.size(); ++i)
        err += std::abs(mean[i] -
                        exactRectLightRectOccluderV(wsPoints[i], {0, 1, 0}, p.light, p.occluder));
    err /= double(mean.size());
    std::printf("[ shadow rays ] mean over 256 rays against the closed form: mae %.4f\n", err);
    EXPECT_LT(err, 0.01);
}

// Per-pixel ray counts (denoiser=rtg's): a count of spp everywhere traces the same bits as none
// given; counts 0 to 4 trace exactly their sum (every ray of this floor reaches the light's side),
// leave the pixels given 0 untraced, and give a pixel of one ray a V of 0 or 1.
TEST(ShadowRays, PerPixelCountsTraceWhatTheyAsk) {
    const PenumbraScene p = makePenumbraScene(8, 8);
    const LocalFrame frame = LocalFrame::fit(p.scene.wsBounds);
    const int W = 20, H = 12;
    std::vector<float> position(4 * W * H), normal(4 * W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::dvec3 ls =
                frame.lsFromWs({-2.0 + 4.0 * (x + 0.5) / W, 0.0, -1.5 + 3.0 * (y + 0.5) / H});
            const size_t i = size_t(y * W + x);
            for (int c = 0; c < 3; ++c) position[4 * i + c] = float(ls[c]);
            position[4 * i + 3] = 1.0f;
            normal[4 * i + 1] = 1.0f;
        }
    const ShadowRayTracer tracer(p.scene, frame);
    const ShadowRayGBuffer g{W, H, position.data(), normal.data()};
    ShadowRaySettings uniform{4, 5, false, 2};
    const ShadowRayFrame all = tracer.trace(g, p.scene.lights[0], uniform);
    const std::vector<uint8_t> four(size_t(W * H), 4);
    ShadowRaySettings given = uniform;
    given.samplesPerPixel = &four;
    const ShadowRayFrame same = tracer.trace(g, p.scene.lights[0], given);
    EXPECT_EQ(same.visibilityAndHit, all.visibilityAndHit);
    EXPECT_EQ(same.raysTraced, all.raysTraced);
    std::vector<uint8_t> counts(size_t(W * H));
    uint64_t sum = 0, nonZero = 0;
    for (size_t i = 0; i < counts.size(); ++i) {
        counts[i] = uint8_t(i % 5);
        sum += counts[i];
        nonZero += counts[i] > 0 ? 1 : 0;
    }
    given.samplesPerPixel = &counts;
    const ShadowRayFrame mixed = tracer.trace(g, p.scene.lights[0], given);
    EXPECT_EQ(mixed.raysTraced, sum);
    EXPECT_EQ(mixed.pixelsTraced, nonZero);
    for (size_t i = 0; i < counts.size(); ++i) {
        const float v = mixed.visibilityAndHit[2 * i];
        if (counts[i] == 0) {
            EXPECT_EQ(v, 0.0f) << i;
        } else if (counts[i] == 1) {
            EXPECT_TRUE(v == 0.0f || v == 1.0f) << i << ": " << v;
        } else if (counts[i] == 4) {
            EXPECT_EQ(v, all.visibilityAndHit[2 * i]) << i;
        }
    }
}

// A sphere light over an open floor: every ray reaches it, so one ray a pixel must give V = 1
// everywhere. Sampled over the whole sphere, the part each point cannot see (G = 0) left most
// pixels without a sample, V = 0: the samples are uniform over the cap the point sees.
TEST(ShadowRays, OneRayAtASphereLightSeesItFromEveryPixel) {
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {8, 0, 0}, {0, 0, -8}, 2, "floor"));
    Light sphere;
    sphere.name = "globe";
    sphere.type = LightType::Sphere;
    sphere.wsPosition = {0.0, 2.0, 0.0};
    sphere.radius = 0.5;
    s.lights = {sphere};
    finalizeScene(s);
    const LocalFrame frame = LocalFrame::fit(s.wsBounds);
    const int W = 16, H = 16;
    std::vector<float> position(4 * W * H), normal(4 * W * H);
    for (int i = 0; i < W * H; ++i) {
        const glm::dvec3 ls =
            frame.lsFromWs({-3.0 + 6.0 * (i % W) / W, 0.0, -3.0 + 6.0 * (i / W) / H});
        for (int c = 0; c < 3; ++c) position[4 * i + c] = float(ls[c]);
        position[4 * i + 3] = 1.0f;
        normal[4 * i + 1] = 1.0f;
    }
    const ShadowRayTracer tracer(s, frame);
    for (int f = 0; f < 4; ++f) {
        const ShadowRayFrame r =
            tracer.trace({W, H, position.data(), normal.data()}, sphere, {1, f, false, 1});
        for (int i = 0; i < W * H; ++i) ASSERT_EQ(r.visibilityAndHit[2 * i], 1.0f) << i;
    }
}

}  // namespace
}  // namespace so::test
