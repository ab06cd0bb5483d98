// denoiser=rtg over a sequence (labels pipeline and gl): issue 63's "done when" on a small image.
// tests/data/anim's box held still (floor.gltf and box.gltf, no animation) under a 2 x 1.5 rect
// light, 16 frames at 64 x 64: Ray Tracing Gems 13's adaptive counts trace fewer rays in the last
// frame than 4 rays everywhere, and its 4-frame mean and variation-sized Gaussian leave a smaller
// penumbra error than those rays' own estimate.
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "compare_run.h"
#include "gl_test_context.h"
#include "raster_compare/pipeline/compare_scene.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kAnim = fs::path(SO_TEST_DATA_DIR) / "anim";

// The sliding box's scene with its box held still and a rect light for its sun.
fs::path writeStillRectScene(const fs::path& dir) {
    fs::create_directories(dir);
    std::ifstream in(kAnim / "sliding_box.scene.json");
    json scene = json::parse(in);
    scene["geometry"] = json::array();
    for (const char* m : {"floor.gltf", "box.gltf"}) {
        fs::copy_file(kAnim / m, dir / m, fs::copy_options::overwrite_existing);
        scene["geometry"].push_back({{"file", m}});
    }
    scene["effects"] = {"penumbra"};  // so that the penumbra metrics are judged
    scene["lights"] = json::array({{{"name", "panel"},
                                    {"type", "rect"},
                                    {"center", {0.5, 4.0, 0.25}},
                                    {"u", {2.0, 0.0, 0.0}},
                                    {"v", {0.0, 0.0, 1.5}}}});
    const fs::path file = dir / "still_rect.scene.json";
    std::ofstream(file) << scene.dump(1);
    return file;
}

// The panel's row of each technique, by label, from `compare SCENE --sequence`.
std::map<std::string, json> panelRows(const fs::path& scene,
                                      const std::vector<std::string>& techniques) {
    CompareOptions o = quickCompareOptions(scene, techniques);
    o.sequence = true;
    const json metrics = compareMetrics(o);
    std::map<std::string, json> rows;
    for (const json& r : metrics["results"]) rows[r["label"]] = r["lights"]["panel"];
    return rows;
}

TEST(RtgSequence, OnAStillRectLightTracesFewerRaysAndHasASmallerPenumbraError) {
    REQUIRE_GL();
    const fs::path dir = fs::temp_directory_path() / ("so_rtg_" + std::to_string(::getpid()));
    const std::string none = "raytraced:spp=4,denoiser=none", rtg = "raytraced:spp=4,denoiser=rtg";
    const std::map<std::string, json> rows = panelRows(writeStillRectScene(dir), {none, rtg});
    fs::remove_all(dir);
    const json &a = rows.at(none), &b = rows.at(rtg);
    ASSERT_EQ(a["sequence"]["frames"], 16) << a.dump();
    const double raysNone = a["cost"]["work"]["rays_traced"].get<double>();
    const double raysRtg = b["cost"]["work"]["rays_traced"].get<double>();
    // Up to 4 rays at every pixel that faces the light: the floor and the box's top and sides.
    EXPECT_GT(raysNone, 4.0 * 1000.0) << a["cost"].dump();
    EXPECT_LT(raysRtg, raysNone) << b["cost"].dump();
    EXPECT_GT(raysRtg, 0.0) << "the sampling matrix traces a quarter of the flat pixels a frame";
    EXPECT_LT(b["penumbra_mae"].get<double>(), a["penumbra_mae"].get<double>())
        << "rtg " << b["penumbra_mae"] << ", none " << a["penumbra_mae"];
}

}  // namespace
}  // namespace so
