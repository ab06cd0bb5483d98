// `trace --frame K` and `--frames A:B` (docs/cli.md): the oracle of a sequence's frame is the
// oracle of a static scene holding that frame's pose (issue 52's sliding box: a glTF translation
// under a sun, 16 frames at 30 fps); a range writes one folder a frame; bad flags exit 2.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"

#include "core/channels.h"
#include "core/image.h"

namespace {

namespace fs = std::filesystem;
using so::test::run;

const fs::path kAnim = fs::path(SO_TEST_DATA_DIR) / "anim";

fs::path tempDir(const std::string& name) {
    const fs::path d =
        fs::temp_directory_path() / ("so_anim_trace_" + std::to_string(::getpid())) / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::vector<float> sunVisibility(const fs::path& exr) {
    const so::ChannelImage image = so::readExr(exr.string());
    const float* v = image.channel(so::channels::lightChannel("sun", so::channels::kVisibility));
    return {v, v + image.pixelCount()};
}

double agreement(const std::vector<float>& a, const std::vector<float>& b) {
    EXPECT_EQ(a.size(), b.size());
    size_t same = 0;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i) same += a[i] == b[i];
    return double(same) / double(a.size());
}

// The box as sliding_box.gltf's clip "slide" places it at t (tests/data/anim/make_anim_gltf.py:
// LINEAR keys x = -2 at t = 0 and x = +2 at t = 0.5 s, both exact in float), in a static scene of
// the same floor and box without animation.
fs::path staticScene(double t) {
    const double x0 = -2.0, x1 = 2.0, t1 = 0.5;
    const double x = x0 + (x1 - x0) * std::min(t, t1) / t1;
    const fs::path dir = tempDir("static");
    for (const char* f : {"floor.gltf", "box.gltf"}) fs::copy_file(kAnim / f, dir / f);
    std::ofstream(dir / "scene.json") << R"({"scene_format": 5,
        "geometry": [{"file": "floor.gltf"}, {"file": "box.gltf", "translate": [)"
                                      << std::to_string(x) << R"(, 0, 0]}],
        "camera": {"eye": [0, 6, 7], "target": [0, 0, 0], "vfov_deg": 45, "width": 64, "height": 64},
        "lights": [{"name": "sun", "type": "directional", "direction": [-0.8, -1, -0.2]}]})";
    return dir / "scene.json";
}

TEST(AnimationTrace, FrameEightIsTheStaticSceneWithTheBoxWhereTheAnimationPutsIt) {
    const fs::path scene = kAnim / "sliding_box.scene.json";
    const fs::path out = tempDir("frame8");
    auto r =
        run("trace " + scene.string() + " --frame 8 --quiet --no-previews --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const fs::path still = staticScene(8.0 / 30.0);
    const fs::path outStill = tempDir("still");
    r = run("trace " + still.string() + " --quiet --no-previews --out " + outStill.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const std::vector<float> frame8 = sunVisibility(out / "oracle.exr");
    EXPECT_GE(agreement(frame8, sunVisibility(outStill / "oracle.exr")), 0.999);

    // The comparison can fail: frame 0's box is elsewhere, and its shadow with it (over ten
    // times the 0.1% the frames may differ by).
    const fs::path out0 = tempDir("frame0");
    r = run("trace " + scene.string() + " --frame 0 --quiet --no-previews --out " + out0.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_LT(agreement(frame8, sunVisibility(out0 / "oracle.exr")), 0.99);
}

TEST(AnimationTrace, ARangeWritesOneFolderAFrameAndVerifiesEach) {
    const fs::path scene = kAnim / "sliding_box.scene.json";
    const fs::path out = tempDir("range");
    auto r = run("trace " + scene.string() + " --frames 7:8 --verify 20 --no-previews --out " +
                 out.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(fs::exists(out / "frame_0007" / "oracle.exr"));
    EXPECT_TRUE(fs::exists(out / "frame_0008" / "oracle.json"));
    EXPECT_FALSE(fs::exists(out / "frame_0009"));
    EXPECT_NE(r.stderrText.find("frame 8 (t = "), std::string::npos) << r.stderrText;
    size_t verified = 0;
    for (size_t at = r.stdoutText.find("verified "); at != std::string::npos;
         at = r.stdoutText.find("verified ", at + 1))
        ++verified;
    EXPECT_EQ(verified, 2u) << r.stdoutText;
    // Each frame's oracle.json says which frame and time it is.
    const nlohmann::json j8 =
        nlohmann::json::parse(std::ifstream(out / "frame_0008" / "oracle.json"));
    EXPECT_EQ(j8["sequence_frame"]["index"], 8);
    EXPECT_DOUBLE_EQ(j8["sequence_frame"]["t"].get<double>(), 8.0 / 30.0);
    const fs::path one = tempDir("one");
    r = run("trace " + scene.string() + " --frame 8 --quiet --no-previews --out " + one.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_EQ(sunVisibility(out / "frame_0008" / "oracle.exr"), sunVisibility(one / "oracle.exr"));
    // A scene traced as its file has it is no frame.
    const fs::path plain = tempDir("plain");
    r = run("trace " + scene.string() + " --quiet --no-previews --out " + plain.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(
        nlohmann::json::parse(std::ifstream(plain / "oracle.json"))["sequence_frame"].is_null());
}

TEST(AnimationTrace, BadFramesExitTwoWithOneLine) {
    const std::string scene = (kAnim / "sliding_box.scene.json").string();
    const std::string out = " --quiet --out " + tempDir("bad").string();
    const std::string plain = (fs::path(SO_TEST_DATA_DIR) / "valid" / "scene.json").string();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {scene + " --frame 16", "--frame: frame 16 is past the sequence's 16 frames"},
        {scene + " --frames 3", "--frames: \"3\" is not A:B"},
        {scene + " --frames 5:2", "--frames: A must not be after B"},
        {scene + " --frames 0:x", "is not A:B"},
        {scene + " --frame -1", "--frame"},
        {scene + " --frame 1 --frames 0:1", "--frame: cannot be used with --frames"},
        {plain + " --frame 0", "the scene has no sequence"},
    };
    for (const auto& [args, message] : cases) {
        auto r = run("trace " + args + out);
        EXPECT_EQ(r.exitCode, 2) << args << ": " << r.stderrText;
        EXPECT_NE(r.stderrText.find(message), std::string::npos) << args << ": " << r.stderrText;
    }
}

}  // namespace
