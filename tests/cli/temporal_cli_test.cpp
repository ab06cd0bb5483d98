// compare --frames-path end to end (label gl): a small scene with a camera path, written by the
// test; metrics.json's rows carry the temporal metrics and the report shows the flicker strip.
#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/scene.h"
#include "gl_test_context.h"
#include "oracle/oracle_cache.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;

int runCompare(const std::string& args, std::string* output) {
    const std::string log = "/tmp/so_path_" + std::to_string(::getpid()) + ".log";
    const int status = std::system(
        (std::string(SO_CLI_PATH) + " compare " + args + " > " + log + " 2>&1").c_str());
    std::ifstream in(log);
    output->assign(std::istreambuf_iterator<char>(in), {});
    fs::remove(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The contact box's floor and box, a point light, and a camera that circles a little.
fs::path writeScene(const fs::path& dir, bool withPath) {
    fs::create_directories(dir / "meshes");
    for (const char* m : {"floor.gltf", "unit_box.gltf"})
        fs::copy_file(fs::path(SO_SCENES_DIR) / "meshes" / m, dir / "meshes" / m,
                      fs::copy_options::overwrite_existing);
    nlohmann::json scene = {
        {"scene_format", withPath ? 2 : 1},
        {"geometry", {{{"file", "meshes/floor.gltf"}}, {{"file", "meshes/unit_box.gltf"}}}},
        {"camera",
         {{"eye", {-5.5, 4.0, -6.0}}, {"target", {0.0, 0.5, 0.0}}, {"width", 96}, {"height", 72}}},
        {"lights", {{{"name", "key"}, {"type", "point"}, {"position", {3.0, 5.0, 2.5}}}}}};
    if (withPath)
        scene["camera_path"] = {
            {"keyframes",
             {{{"t", 0}, {"eye", {-5.5, 4.0, -6.0}}, {"target", {0.0, 0.5, 0.0}}},
              {{"t", 1}, {"eye", {-6.0, 4.2, -5.4}}, {"target", {0.0, 0.5, 0.0}}}}}};
    const fs::path file = dir / (withPath ? "path.scene.json" : "still.scene.json");
    std::ofstream(file) << scene.dump(1);
    return file;
}

TEST(ComparePath, RowsCarryTemporalFlickerAndTheReportItsStrip) {
    REQUIRE_GL();
    const fs::path dir = fs::temp_directory_path() / ("so_path_e2e_" + std::to_string(::getpid()));
    const fs::path scene = writeScene(dir, true);
    std::string log;
    // A coarse map swims as the camera moves: something to show in the strip.
    ASSERT_EQ(runCompare(scene.string() + " --frames 1 --frames-path 3 --no-cache --embed-images " +
                             "--out " + (dir / "out").string() +
                             " --technique basic:resolution=64 --technique volume-zfail",
                         &log),
              0)
        << log;
    EXPECT_NE(log.find("camera path: frame 3 of 3"), std::string::npos) << log;
    std::ifstream in(dir / "out" / "metrics.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["results"].size(), 2u);
    std::map<std::string, double> flicker;
    for (const auto& r : j["results"]) {
        const auto& key = r["lights"]["key"];
        ASSERT_TRUE(key["temporal_flicker_rate"].is_number()) << key.dump();
        flicker[r["label"].get<std::string>()] = key["temporal_flicker_rate"].get<double>();
        EXPECT_LE(key["temporal_flicker_rate"].get<double>(), 1.0);
        EXPECT_GT(key["temporal_tracked_pairs"].get<size_t>(), 300u);
        EXPECT_EQ(key["temporal_frames"].get<int>(), 3);
    }
    // The coarse map's errors move with the camera; the exact shadow volumes' do not.
    EXPECT_GT(flicker["basic:resolution=64"], 0.0);
    EXPECT_LT(flicker["volume-zfail"], flicker["basic:resolution=64"]);
    std::ifstream cin(dir / "out" / "metrics.csv");
    const std::string csv((std::istreambuf_iterator<char>(cin)), {});
    EXPECT_NE(csv.find(",temporal_flicker_rate,"), std::string::npos);
    std::ifstream rin(dir / "out" / "report.html");
    const std::string report((std::istreambuf_iterator<char>(rin)), {});
    EXPECT_NE(report.find("temporal flicker"), std::string::npos) << "the summary's column";
    const size_t strip = report.find("id=\"flicker-strip-0\"");
    ASSERT_NE(strip, std::string::npos) << "no strip: did nothing flicker?";
    EXPECT_NE(report.find("<b>basic:resolution=64</b>"), std::string::npos)
        << "the coarse map flickers most";
    size_t images = 0;
    for (size_t at = report.find("data:image/png", strip); at != std::string::npos;
         at = report.find("data:image/png", at + 1))
        ++images;
    EXPECT_GE(images, 4u);
    // The gate reads the metric: a zero limit fails on the flickering technique, a loose one holds.
    const std::string metrics = (dir / "out" / "metrics.json").string();
    std::ofstream(dir / "strict.json")
        << R"({"limits_format": 1, "default": {"temporal_flicker_rate": 0}})";
    std::ofstream(dir / "loose.json")
        << R"({"limits_format": 1, "default": {"temporal_flicker_rate": 1}})";
    const auto gate = [&](const std::string& limits) {
        const int status = std::system((std::string(SO_CLI_PATH) + " gate " + metrics +
                                        " --limits " + (dir / limits).string() + " > /dev/null")
                                           .c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    EXPECT_EQ(gate("strict.json"), 1);
    EXPECT_EQ(gate("loose.json"), 0);
    fs::remove_all(dir);
}

TEST(ComparePath, QuietLeavesOutTheProgressLines) {
    REQUIRE_GL();
    const fs::path dir =
        fs::temp_directory_path() / ("so_path_quiet_" + std::to_string(::getpid()));
    const fs::path scene = writeScene(dir, true);
    const std::string args = scene.string() +
                             " --width 32 --height 24 --frames 1 --warmup 0 --frames-path 2 "
                             "--no-cache --technique basic:resolution=64 --out " +
                             (dir / "out").string();
    std::string loud, quiet;
    ASSERT_EQ(runCompare(args, &loud), 0) << loud;
    ASSERT_EQ(runCompare(args + " --quiet", &quiet), 0) << quiet;
    EXPECT_NE(loud.find("camera path: frame 2 of 2"), std::string::npos) << loud;
    EXPECT_NE(loud.find("rendering basic"), std::string::npos) << loud;
    EXPECT_EQ(quiet.find("camera path: frame"), std::string::npos) << quiet;
    EXPECT_EQ(quiet.find("rendering"), std::string::npos) << quiet;
    EXPECT_NE(quiet.find("compared "), std::string::npos) << "the summary stays: " << quiet;
    fs::remove_all(dir);
}

TEST(ComparePath, NoPathOrTooFewFramesIsAOneLineError) {
    REQUIRE_GL();
    const fs::path dir = fs::temp_directory_path() / ("so_path_err_" + std::to_string(::getpid()));
    const fs::path still = writeScene(dir, false);
    std::string log;
    EXPECT_EQ(runCompare(still.string() + " --frames-path 3 --no-cache --out " +
                             (dir / "out").string() + " --technique basic",
                         &log),
              2);
    EXPECT_NE(log.find(still.string() + ": camera_path: missing"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out" / "metrics.json")) << "checked before any work";
    const fs::path path = writeScene(dir, true);
    EXPECT_NE(runCompare(path.string() + " --frames-path 1 --no-cache --out " +
                             (dir / "out").string() + " --technique basic",
                         &log),
              0);
    EXPECT_NE(log.find("--frames-path"), std::string::npos) << log;
    fs::remove_all(dir);
}

// A path frame's oracle must never come back for another pose, nor for the scene camera; and the
// scene camera's keys stay those of before camera overrides existed.
TEST(OracleCacheKey, CameraOverrideIsInTheKey) {
    const fs::path dir = fs::temp_directory_path() / ("so_path_key_" + std::to_string(::getpid()));
    const Scene scene = loadScene(writeScene(dir, true));
    OracleOptions plain;
    OracleOptions same = plain;
    same.camera = scene.camera;
    OracleOptions moved = same;
    moved.camera->wsEye.x += 1e-9;
    const std::string k0 = oracleCacheKey(scene, plain), k1 = oracleCacheKey(scene, same),
                      k2 = oracleCacheKey(scene, moved);
    EXPECT_NE(k0, k1);
    EXPECT_NE(k1, k2);
    EXPECT_EQ(k2, oracleCacheKey(scene, moved));
    EXPECT_EQ(effectiveCamera(scene, moved).wsEye, moved.camera->wsEye);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so
