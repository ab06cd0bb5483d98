// Ghosting is its own class (issue 64; labels pipeline and gl), on tests/data/anim's sliding box
// (a unit box a glTF translation slides from x = -2 to x = +2 over 0.5 s, 16 frames at 64 x 64),
// under its sun and under a sampled rect light: a ray-traced shadow has no depth comparison to acne
// with, so no denoiser has acne; the trail a denoiser's history leaves behind the box is ghosting
// (sequence.ghosting_rate), drawn in the last frame's error map (its EXR layer, the report's
// legend). Before, the geometric rule called the trails acne: at 160 x 120 on scenes/sliding_box's
// sun 0.0021 (temporal, hitdist) and 0.0025 (rtg); under a rect light 0.0910 for svgf.
#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "compare_run.h"
#include "core/image.h"
#include "gl_test_context.h"
#include "raster_compare/pipeline/compare_scene.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kAnim = fs::path(SO_TEST_DATA_DIR) / "anim";

const std::vector<std::string>& denoisers() {
    static const std::vector<std::string> all = [] {
        std::vector<std::string> out;
        for (const char* d : {"none", "temporal", "svgf", "ffx", "hitdist", "rtg"})
            out.push_back(std::string("raytraced:spp=1,denoiser=") + d);
        return out;
    }();
    return all;
}

// The sliding box with a 1 x 1 rect light facing down for its sun, its penumbra sampled.
fs::path writeRectScene(const fs::path& dir) {
    fs::create_directories(dir);
    std::ifstream in(kAnim / "sliding_box.scene.json");
    json scene = json::parse(in);
    fs::copy_file(kAnim / "sliding_box.gltf", dir / "sliding_box.gltf",
                  fs::copy_options::overwrite_existing);
    scene["effects"] = {"hard", "penumbra"};
    scene["lights"] = json::array({{{"name", "panel"},
                                    {"type", "rect"},
                                    {"center", {-1.0, 4.0, 1.0}},
                                    {"u", {1.0, 0.0, 0.0}},
                                    {"v", {0.0, 0.0, 1.0}}}});
    const fs::path file = dir / "sliding_rect.scene.json";
    std::ofstream(file) << scene.dump(1);
    return file;
}

// The rows of `light`, by label, from `compare SCENE --sequence` written to `out`.
std::map<std::string, json> lightRows(const fs::path& scene, const std::string& light,
                                      const fs::path& out) {
    CompareOptions o = quickCompareOptions(scene, denoisers());
    o.sequence = true;
    o.outDir = out.string();
    o.embedImages = true;
    const json metrics = compareMetrics(o);
    std::map<std::string, json> rows;
    for (const json& r : metrics["results"]) rows[r["label"]] = r["lights"][light];
    return rows;
}

// Every denoiser: acne 0, a ghosting rate; svgf's above 0.
void expectNoAcneAndSvgfGhosts(const std::map<std::string, json>& rows, const char* light) {
    for (const std::string& t : denoisers()) {
        const json& row = rows.at(t);
        EXPECT_EQ(row["acne_rate"].get<double>(), 0.0) << t;
        ASSERT_TRUE(row["sequence"]["ghosting_rate"].is_number()) << t << row["sequence"];
        std::printf("[ ghosting ] sliding box, %s: %s ghosting_rate %.4f (%d pixel-frames)\n",
                    light, t.c_str(), row["sequence"]["ghosting_rate"].get<double>(),
                    row["sequence"]["ghosting_pixels"].get<int>());
    }
    const json& svgf = rows.at("raytraced:spp=1,denoiser=svgf")["sequence"];
    EXPECT_GT(svgf["ghosting_rate"].get<double>(), 0.0);
    EXPECT_GT(svgf["ghosting_pixels"].get<size_t>(), 0u);
}

// Whether svgf's error EXR has a ghosting pixel for `light`.
bool svgfGhostDrawn(const fs::path& out, const std::string& light) {
    for (const auto& entry : fs::directory_iterator(out)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("error_", 0) != 0 || name.find("svgf") == std::string::npos) continue;
        const ChannelImage errors = readExr(entry.path().string());
        if (!errors.has(light + ".ghosting")) return false;
        const float* g = errors.channel(light + ".ghosting");
        return std::any_of(g, g + errors.pixelCount(), [](float v) { return v == 1.0f; });
    }
    return false;
}

TEST(GhostingSequence, UnderTheSunNoDenoiserHasAcneAndSvgfsTrailIsGhosting) {
    REQUIRE_GL();
    const fs::path out = fs::temp_directory_path() / ("so_ghost_sun_" + std::to_string(::getpid()));
    const std::map<std::string, json> rows =
        lightRows(kAnim / "sliding_box.scene.json", "sun", out);
    expectNoAcneAndSvgfGhosts(rows, "sun");
    // One ray to the sun is exact: without a history there is no trail.
    EXPECT_EQ(rows.at("raytraced:spp=1,denoiser=none")["sequence"]["ghosting_pixels"], 0);
    EXPECT_TRUE(svgfGhostDrawn(out, "sun")) << "svgf's last frame has a trail";
    std::ifstream page(out / "report.html");
    const std::string html(std::istreambuf_iterator<char>(page), {});
    EXPECT_NE(html.find("</i>ghosting</span>"), std::string::npos);
    fs::remove_all(out);
}

TEST(GhostingSequence, UnderARectLightNoDenoiserHasAcneAndSvgfsTrailIsGhosting) {
    REQUIRE_GL();
    const fs::path dir =
        fs::temp_directory_path() / ("so_ghost_rect_" + std::to_string(::getpid()));
    const std::map<std::string, json> rows = lightRows(writeRectScene(dir), "panel", dir / "out");
    expectNoAcneAndSvgfGhosts(rows, "panel");
    EXPECT_TRUE(rows.at("raytraced:spp=1,denoiser=svgf")["penumbra_mae"].is_number())
        << "the rect light is sampled";
    EXPECT_TRUE(svgfGhostDrawn(dir / "out", "panel"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so
