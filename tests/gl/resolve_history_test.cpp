// resolve=history on the GPU (raster_compare/gl/resolves/history.glsl) against its CPU reference,
// time/shadow_history.h's ShadowHistory, on tests/data/anim's sliding box (a box a glTF
// translation slides across a floor under a sun, 16 frames): each frame is rendered with one
// TemporalState for pcf:temporal=on with resolve=none (the raw jittered V, which the CPU history
// resolves) and with resolve=history (resolved on the GPU through the same camera and mesh
// motion). The two agree but where float and double round a same-surface test or a bilinear
// weight apart. Label "gl".
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "core/scene.h"
#include "core/scene_pose.h"
#include "gl_test_context.h"
#include "raster_compare/gl/time/shadow_history.h"
#include "raster_compare/gl/time/temporal_state.h"

namespace so::test {
namespace {

TEST(ResolveHistory, TheGpuHistoryIsTheCpuReferenceOnTheSlidingBox) {
    REQUIRE_GL();
    Scene scene = loadScene(std::string(SO_TEST_DATA_DIR) + "/anim/sliding_box.scene.json");
    scene.camera.width = 96;
    scene.camera.height = 72;
    ASSERT_TRUE(scene.sequence);
    const std::string light = scene.lights.at(0).name;
    const auto raw = createTechnique("pcf", {"temporal=on", "resolve=none"});
    const auto gpu = createTechnique("pcf", {"temporal=on", "resolve=history"});
    ShadowHistory cpu({0.9, true}, light);
    TemporalState state;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    o.countWork = false;
    o.temporal = &state;
    double tBefore = 0.0;
    size_t compared = 0, apart = 0, moved = 0;
    double worst = 0.0;
    for (int f = 0; f < scene.sequence->frames; ++f) {
        const double t = sequenceTime(*scene.sequence, f);
        std::vector<glm::dmat4> motion;
        for (size_t m = 0; f > 0 && m < scene.meshes.size(); ++m)
            motion.push_back(meshMotion(scene, m, t, tBefore));
        state.beginFrame(f, motion);
        o.frameIndex = f;
        const Scene posed = sceneAtTime(scene, t);
        std::vector<RasterResult> results(2);
        renderInterleaved(
            posed, {raw.get(), gpu.get()}, o, *gl,
            {nullptr, [&](size_t k, RasterResult&& r) { results[k] = std::move(r); }});
        const std::vector<float> reference =
            cpu.resolve(scene, {&results[0].image, posed.camera, t});
        const float* resolved =
            results[1].image.channel(channels::lightChannel(light, channels::kVisibility));
        const float* unresolved =
            results[0].image.channel(channels::lightChannel(light, channels::kVisibility));
        for (size_t i = 0; i < reference.size(); ++i) {
            ++compared;
            const double d = std::abs(double(reference[i]) - resolved[i]);
            worst = std::max(worst, d);
            apart += d > 1e-4;
            moved += std::abs(double(reference[i]) - unresolved[i]) > 1e-3;
        }
        EXPECT_EQ(results[1].stats.historyFrames, f == 0 ? 0 : f + 1) << f;
        tBefore = t;
    }
    std::printf(
        "[ history ] %zu pixel-frames, %zu resolved away from the raw V, %zu apart from the "
        "CPU reference by more than 1e-4 (worst %.3g)\n",
        compared, moved, apart, worst);
    EXPECT_GT(moved, compared / 100) << "the history changed nothing: nothing was compared";
    EXPECT_LE(apart, compared / 1000);
}

// raster --converge N (renderConverged): N still frames with one temporal state, the last returned;
// history_frames says how many frames its V holds: N for a resolve that keeps a history, 0 on a
// cold start, none for a technique that resolves nothing.
TEST(ResolveHistory, ConvergedRendersSayHowManyFramesTheirVHolds) {
    REQUIRE_GL();
    Scene scene = loadScene(std::string(SO_TEST_DATA_DIR) + "/anim/sliding_box.scene.json");
    scene.camera.width = 64;
    scene.camera.height = 48;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    o.countWork = false;
    for (const char* resolve : {"resolve=taa", "resolve=history"}) {
        const auto t = createTechnique("pcf", {"temporal=on", resolve});
        o.converge = 1;
        EXPECT_EQ(renderConverged(scene, *t, o, *gl).stats.historyFrames, 0) << resolve;
        o.converge = 8;
        EXPECT_EQ(renderConverged(scene, *t, o, *gl).stats.historyFrames, 8) << resolve;
    }
    EXPECT_FALSE(renderConverged(scene, *createTechnique("pcf", {}), o, *gl).stats.historyFrames);
    EXPECT_FALSE(
        renderConverged(scene, *createTechnique("pcf", {"temporal=on", "resolve=none"}), o, *gl)
            .stats.historyFrames);
}

}  // namespace
}  // namespace so::test
