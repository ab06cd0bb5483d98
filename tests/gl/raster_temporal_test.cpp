// temporal=on of pcf and pcss (docs/techniques.md#temporal): the taps turn with the frame index
// (interleaved gradient noise over a Vogel disk), deterministically, and their mean over frames is
// the filter the still pattern approximates; temporal=off does not see the frame index at all.
// Label "gl". (That temporal=off renders what pcf and pcss rendered before it existed, every
// channel bit for bit, was checked on the shipped scenes when it was added: see the commit.)
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "core/scene.h"
#include "gl_test_context.h"

namespace so::test {
namespace {

// The light's V of one untimed frame at frame index `frame`.
std::vector<float> visibilityAt(const Scene& scene, const std::string& technique,
                                const std::vector<std::string>& settings, int frame) {
    std::string why;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    o.countWork = false;
    o.frameIndex = frame;
    const RasterResult r =
        renderRaster(scene, *createTechnique(technique, settings), o, *glContext(why));
    const float* v = r.image.channel(channels::lightChannel("panel", channels::kVisibility));
    return {v, v + r.image.pixelCount()};
}

// The shipped penumbra_square, small, with a coarse map: a penumbra some pixels wide.
Scene smallPenumbraSquare() {
    Scene s = loadScene(std::string(SO_SCENES_DIR) + "/penumbra_square.scene.json");
    s.camera.width = 96;
    s.camera.height = 72;
    return s;
}

bool inPenumbra(float v) {
    return v > 0.0f && v < 1.0f;
}

TEST(TemporalTaps, OffIgnoresTheFrameIndex) {
    REQUIRE_GL();
    const Scene s = smallPenumbraSquare();
    for (const char* technique : {"pcf", "pcss"}) {
        const std::vector<float> v0 = visibilityAt(s, technique, {"resolution=256"}, 0);
        EXPECT_EQ(visibilityAt(s, technique, {"resolution=256"}, 7), v0) << technique;
        EXPECT_EQ(visibilityAt(s, technique, {"resolution=256", "temporal=off"}, 7), v0);
    }
}

TEST(TemporalTaps, OnTurnsWithTheFrameAndRepeatsItself) {
    REQUIRE_GL();
    const Scene s = smallPenumbraSquare();
    for (const char* technique : {"pcf", "pcss"}) {
        const std::vector<std::string> on = {"resolution=256", "temporal=on", "resolve=none"};
        const std::vector<float> a = visibilityAt(s, technique, on, 3);
        EXPECT_EQ(visibilityAt(s, technique, on, 3), a) << technique << ": not deterministic";
        const std::vector<float> b = visibilityAt(s, technique, on, 4);
        size_t penumbra = 0, differ = 0;
        for (size_t i = 0; i < a.size(); ++i) {
            if (!inPenumbra(a[i]) && !inPenumbra(b[i])) continue;
            ++penumbra;
            differ += a[i] != b[i];
        }
        std::printf("[ temporal ] %s: %zu of %zu penumbra pixels differ between frames 3 and 4\n",
                    technique, differ, penumbra);
        ASSERT_GT(penumbra, 50u) << technique;
        // Every pixel's taps turn by another angle (a few may round to the same count of taps).
        EXPECT_GT(differ, penumbra / 2) << technique;
    }
}

// Each pixel's Vogel disk turns from frame to frame, so the mean over frames converges (two
// disjoint sets of 16 frames agree better than two frames do) to a disk filter of the area of the
// grid's square, close to pcf's own grid: on an edge a box and a disk of one area differ by a few
// hundredths. With 49 taps (kernel 7) measured here: frame to frame 0.016, mean to mean 0.007,
// mean to grid 0.034 (mean |dV| over the penumbra). Not with 9 (kernel 3: 0.074, 0.043, 0.099):
// the frame offset (5.588238 pixels) advances each pixel's angle by 0.598 or 0.616 of a turn a
// frame, a sequence that averages out more slowly than independent angles for few taps
// (docs/techniques.md#temporal).
TEST(TemporalTaps, TheMeanOverFramesConvergesToTheStillFilter) {
    REQUIRE_GL();
    const Scene s = smallPenumbraSquare();
    for (const char* kernel : {"kernel=7"}) {
        const std::vector<float> grid = visibilityAt(s, "pcf", {"resolution=128", kernel}, 0);
        const int frames = 16;
        std::vector<double> meanA(grid.size(), 0.0), meanB(grid.size(), 0.0);
        std::vector<float> frame0, frame1;
        for (int f = 0; f < 2 * frames; ++f) {
            const std::vector<float> v = visibilityAt(
                s, "pcf", {"resolution=128", kernel, "temporal=on", "resolve=none"}, f);
            if (f == 0) frame0 = v;
            if (f == 1) frame1 = v;
            for (size_t i = 0; i < v.size(); ++i)
                (f < frames ? meanA : meanB)[i] += v[i] / double(frames);
        }
        double toGrid = 0.0, betweenMeans = 0.0, betweenFrames = 0.0;
        size_t penumbra = 0;
        for (size_t i = 0; i < grid.size(); ++i) {
            if (!inPenumbra(grid[i])) continue;
            ++penumbra;
            toGrid += std::abs(0.5 * (meanA[i] + meanB[i]) - grid[i]);
            betweenMeans += std::abs(meanA[i] - meanB[i]);
            betweenFrames += std::abs(double(frame0[i]) - frame1[i]);
        }
        ASSERT_GT(penumbra, 50u) << kernel;
        toGrid /= double(penumbra);
        betweenMeans /= double(penumbra);
        betweenFrames /= double(penumbra);
        std::printf(
            "[ temporal ] pcf %s, %zu penumbra pixels: mean |frame 0 - frame 1| %.4f, "
            "|mean of 16 - mean of 16| %.4f, |mean of 32 - grid| %.4f\n",
            kernel, penumbra, betweenFrames, betweenMeans, toGrid);
        EXPECT_LT(betweenMeans, 0.5 * betweenFrames) << kernel;
        EXPECT_LT(toGrid, 0.05) << kernel;
    }
}

}  // namespace
}  // namespace so::test
