// pcf:pattern=three|bevy|godot, the tap patterns engines ship (issue 63; pcf.cpp cites their
// sources): three.js turns its taps by the pixel alone (no frame term), Bevy by the pixel moved by
// frame % 64, Godot by the pixel moved by the frame; each tap is one hardware 2x2 compare, 5, 8
// and 4 of them. Label "gl" (the provenance and settings checks need no GL but live here beside
// the patterns they describe).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/channels.h"
#include "core/error.h"
#include "core/scene.h"
#include "gl_test_context.h"
#include "raster_compare/gl/resolves/resolve.h"
#include "raster_compare/gl/technique.h"
#include "test_scenes.h"

namespace so::test {
namespace {

// The panel's V of one untimed frame at frame index `frame`.
std::vector<float> visibilityAt(const Scene& scene, const std::vector<std::string>& settings,
                                int frame) {
    std::string why;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    o.countWork = false;
    o.frameIndex = frame;
    const RasterResult r =
        renderRaster(scene, *createTechnique("pcf", settings), o, *glContext(why));
    const float* v = r.image.channel(channels::lightChannel("panel", channels::kVisibility));
    return {v, v + r.image.pixelCount()};
}

// The shipped penumbra_square, small; the tests take a 64-texel map, so that the engines' filters
// of 1 to 2 texels spread over some pixels.
Scene smallPenumbraSquare() {
    Scene s = loadScene(std::string(SO_SCENES_DIR) + "/penumbra_square.scene.json");
    s.camera.width = 96;
    s.camera.height = 72;
    return s;
}

// Of the pixels in a penumbra in either image, how many differ (printed, for the record).
struct Difference {
    size_t penumbra = 0, differ = 0;
};
Difference differenceOf(const std::vector<float>& a, const std::vector<float>& b) {
    Difference d;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!(a[i] > 0.0f && a[i] < 1.0f) && !(b[i] > 0.0f && b[i] < 1.0f)) continue;
        ++d.penumbra;
        d.differ += a[i] != b[i];
    }
    return d;
}

TEST(EnginePatterns, ThreeHasNoFrameTerm) {
    REQUIRE_GL();
    const Scene s = smallPenumbraSquare();
    const std::vector<std::string> three = {"resolution=64", "pattern=three"};
    const std::vector<float> v0 = visibilityAt(s, three, 0);
    const Difference d = differenceOf(v0, visibilityAt(s, three, 5));
    std::printf("[ patterns ] three: %zu of %zu penumbra pixels differ between frames 0 and 5\n",
                d.differ, d.penumbra);
    ASSERT_GT(d.penumbra, 50u);
    EXPECT_EQ(d.differ, 0u);
    // The pixel turns it: the pattern is not the grid's, nor the same disk at every pixel.
    EXPECT_NE(v0, visibilityAt(s, {"resolution=64"}, 0));
}

TEST(EnginePatterns, BevyTurnsWithTheFrameModulo64) {
    REQUIRE_GL();
    const Scene s = smallPenumbraSquare();
    const std::vector<std::string> bevy = {"resolution=64", "pattern=bevy"};
    const std::vector<float> v3 = visibilityAt(s, bevy, 3);
    const Difference next = differenceOf(v3, visibilityAt(s, bevy, 4));
    std::printf("[ patterns ] bevy: %zu of %zu penumbra pixels differ between frames 3 and 4\n",
                next.differ, next.penumbra);
    ASSERT_GT(next.penumbra, 50u);
    EXPECT_GT(next.differ, next.penumbra / 2);
    EXPECT_EQ(visibilityAt(s, bevy, 3 + 64), v3) << "frame % 64: frame 67 is frame 3";
}

// Godot 4.6 turns its soft shadows by taa_frame_count = frame_number % jitter_phase_count, 16 with
// TAA, and by nothing (0) without TAA or FSR2 (renderer_scene_cull.cpp): pcf:pattern=godot turns
// per frame only with its TAA (temporal=on, resolve=taa), with a period of 16 frames.
TEST(EnginePatterns, GodotTurnsWithTheFrameModulo16UnderItsTaaOnly) {
    REQUIRE_GL();
    const Scene s = smallPenumbraSquare();
    const std::vector<std::string> still = {"resolution=64", "pattern=godot"},
                                   taa = {"resolution=64", "pattern=godot", "temporal=on"};
    EXPECT_EQ(visibilityAt(s, still, 4), visibilityAt(s, still, 3)) << "no TAA: no frame term";
    const std::vector<float> v3 = visibilityAt(s, taa, 3);
    const Difference next = differenceOf(v3, visibilityAt(s, taa, 4));
    ASSERT_GT(next.penumbra, 50u);
    EXPECT_GT(next.differ, next.penumbra / 2);
    EXPECT_EQ(visibilityAt(s, taa, 3 + 16), v3) << "frame % 16: frame 19 is frame 3";
}

const RasterLightStats& light(const RasterResult& r, const std::string& name) {
    for (const RasterLightStats& l : r.stats.lights)
        if (l.name == name) return l;
    throw std::runtime_error("no light " + name);
}

// Each tap is one hardware compare of 2 x 2 texels: 5 (three), 8 (bevy), 4 (godot) taps per lit
// receiver fragment. Every surface seen here faces the sun and the point light and lies in their
// maps, so every visibility fragment is a lit receiver.
TEST(EnginePatterns, WorkCountsTheEnginesTapCounts) {
    REQUIRE_GL();
    const Scene s = makeSquareOccluderScene(96, 72).scene;
    const RasterResult grid = renderOneFrame(s, "pcf", {"resolution=512"});
    for (const auto& [pattern, taps] :
         std::vector<std::pair<std::string, uint64_t>>{{"three", 5}, {"bevy", 8}, {"godot", 4}}) {
        const RasterResult r = renderOneFrame(s, "pcf", {"resolution=512", "pattern=" + pattern});
        for (const char* l : {"sun", "point"}) {
            const uint64_t fragments = light(grid, l).workByPass.at("visibility").counts.fragments;
            ASSERT_GT(fragments, 1000u);
            const PassWork& p = light(r, l).workByPass.at("visibility");
            EXPECT_EQ(p.counts.fragments, fragments) << pattern << " " << l;
            EXPECT_EQ(p.counts.textureTaps, taps * fragments) << pattern << " " << l;
            EXPECT_EQ(p.tapBytes, taps * fragments * 4 * 4) << pattern << " " << l;  // 2x2 texels
        }
    }
}

TEST(EnginePatterns, EachPatternNamesItsSource) {
    const ParamTable& table = findTechnique("pcf").params;
    const auto spec = std::find_if(table.begin(), table.end(),
                                   [](const ParamSpec& s) { return s.name == "pattern"; });
    ASSERT_NE(spec, table.end());
    ASSERT_EQ(spec->provenances.size(), spec->names.size());
    for (size_t i = 0; i < spec->names.size(); ++i) {
        EXPECT_NO_THROW(checkProvenance(spec->provenances[i], "pcf:pattern=" + spec->names[i]));
        const bool engine = i >= 2;  // three, bevy, godot
        EXPECT_EQ(spec->provenances[i].fidelity == Fidelity::Variant, engine) << spec->names[i];
    }
    EXPECT_NE(spec->provenances[2].anchor.find("three.js"), std::string::npos);
    EXPECT_NE(spec->provenances[3].anchor.find("Bevy"), std::string::npos);
    EXPECT_NE(spec->provenances[4].anchor.find("Godot"), std::string::npos);
}

// three.js's taps have no frame term and nothing resolves them: temporal=on with them is an error
// naming the key. Bevy's and Godot's turn per frame as the engines turn them; temporal=on resolves
// them over frames (`resolve`) and changes nothing in their shader.
TEST(EnginePatterns, TemporalOnResolvesTheTurningEnginePatternsOnly) {
    try {
        createTechnique("pcf", {"pattern=three", "temporal=on"});
        ADD_FAILURE() << "pattern=three: no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "temporal");
    }
    for (const char* pattern : {"pattern=three", "pattern=bevy", "pattern=godot"})
        EXPECT_EQ(createTechnique("pcf", {pattern})->resolve(), nullptr) << pattern;
    for (const char* pattern : {"pattern=bevy", "pattern=godot"}) {
        const auto on = createTechnique("pcf", {pattern, "temporal=on"});
        ASSERT_NE(on->resolve(), nullptr) << pattern;
        EXPECT_EQ(on->resolve()->name(), "taa") << pattern;
    }
    EXPECT_NO_THROW(createTechnique("pcf", {"pattern=poisson", "temporal=on"}));
}

}  // namespace
}  // namespace so::test
