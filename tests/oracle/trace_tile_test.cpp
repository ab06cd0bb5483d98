// `trace --tile I/N` and `trace-merge`: the bands of an image, traced apart and joined, give the
// whole run's oracle.exr byte for byte; tiles that do not belong together are refused with one
// line naming the folder's file and the field (exit 2).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"

#include "core/image.h"

namespace {

namespace fs = std::filesystem;

using so::test::readBytes;
using so::test::run;
using so::test::RunResult;

nlohmann::json readJson(const fs::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

// The merged oracle.json against the whole run's: equal but for times (and what is derived from
// them), the thread count and the merge's own record; recomputed means to rounding.
void expectStatsMatch(const nlohmann::json& merged, const nlohmann::json& whole,
                      const std::string& path = "") {
    if (path.find("seconds") != std::string::npos || path.find("per_second") != std::string::npos ||
        path == ".threads" || path == ".merged_tiles")
        return;
    if (merged.is_number() && whole.is_number() && !merged.is_number_integer()) {
        EXPECT_NEAR(merged.get<double>(), whole.get<double>(),
                    1e-12 * std::abs(whole.get<double>()))
            << path;
    } else if (merged.is_object() && whole.is_object()) {
        for (auto it = whole.begin(); it != whole.end(); ++it) {
            EXPECT_TRUE(merged.contains(it.key())) << path << "." << it.key();
            if (merged.contains(it.key()))
                expectStatsMatch(merged[it.key()], it.value(), path + "." + it.key());
        }
    } else if (merged.is_array() && whole.is_array() && merged.size() == whole.size()) {
        for (size_t i = 0; i < whole.size(); ++i)
            expectStatsMatch(merged[i], whole[i], path + "[" + std::to_string(i) + "]");
    } else {
        EXPECT_EQ(merged, whole) << path;
    }
}

// A hard light (the sun) and a sampled area light (the panel), alpha-tested occluders.
const std::string kScene = std::string(SO_SCENES_DIR) + "/alpha_grate.scene.json";
// 46 rows: 12 rows of 4x4 tiles, the last one short.
const std::string kSize = " --width 64 --height 46 --threads 2 --quiet";
const std::string kOptions = kSize + " --spp 32";

// A fresh folder per test, removed at the end.
class TraceTile : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("so_trace_tile_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Traces band i of n into dir_/name (or the whole image without n); expects success.
    std::string trace(const std::string& name, const std::string& tile = "",
                      const std::string& extra = "", const std::string& scene = kScene,
                      const std::string& options = kOptions) {
        const std::string out = (dir_ / name).string();
        const RunResult r = run("trace " + scene + " --out " + out + options + extra +
                                (tile.empty() ? "" : " --tile " + tile));
        EXPECT_EQ(r.exitCode, 0) << r.stderrText;
        return out;
    }
    RunResult merge(const std::vector<std::string>& dirs, const std::string& out) {
        std::string args = "trace-merge";
        for (const std::string& d : dirs) args += " " + d;
        return run(args + " --out " + (dir_ / out).string() + " --quiet");
    }
    // Exit 2, one line, naming `field`.
    static void expectInputError(const RunResult& r, const std::string& field) {
        EXPECT_EQ(r.exitCode, 2) << r.stderrText;
        EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
        EXPECT_NE(r.stderrText.find(field), std::string::npos) << r.stderrText;
    }

    fs::path dir_;
};

TEST_F(TraceTile, MergeIsByteIdenticalToTheWholeTrace) {
    const std::string whole = trace("whole");
    const std::string wholeExr = readBytes(fs::path(whole) / "oracle.exr");
    ASSERT_FALSE(wholeExr.empty());
    const nlohmann::json wholeJson = readJson(fs::path(whole) / "oracle.json");
    // 1 band; 3 (12 tile rows: 16 + 16 + 14 rows); 5 (uneven: 2, 2, 3, 2, 3 tile rows).
    for (int n : {1, 3, 5}) {
        std::vector<std::string> dirs;
        for (int i = n - 1; i >= 0; --i)  // any order
            dirs.push_back(trace("n" + std::to_string(n) + "_" + std::to_string(i),
                                 std::to_string(i) + "/" + std::to_string(n)));
        const std::string out = "merged" + std::to_string(n);
        const RunResult r = merge(dirs, out);
        ASSERT_EQ(r.exitCode, 0) << r.stderrText;
        EXPECT_TRUE(readBytes(dir_ / out / "oracle.exr") == wholeExr) << "N = " << n;
        for (const char* png : {"sun.png", "panel.png"})
            EXPECT_TRUE(readBytes(dir_ / out / png) == readBytes(fs::path(whole) / png)) << png;
        // Sums of counts are exact; the tile block is gone.
        const nlohmann::json j = readJson(dir_ / out / "oracle.json");
        EXPECT_FALSE(j.contains("tile"));
        EXPECT_EQ(j["merged_tiles"]["count"], n);
        expectStatsMatch(j, wholeJson);
    }
}

TEST_F(TraceTile, AdaptiveSamplingWithContactRaysMergesByteIdentically) {
    // Adaptive stopping, a sphere light and its contact (closest-hit) rays.
    const std::string scene = std::string(SO_SCENES_DIR) + "/sphere_light.scene.json";
    const std::string adaptive = kSize + " --target-error 0.05";
    const std::string whole = trace("whole", "", "", scene, adaptive);
    std::vector<std::string> dirs;
    for (int i = 0; i < 4; ++i)
        dirs.push_back(
            trace("t" + std::to_string(i), std::to_string(i) + "/4", "", scene, adaptive));
    const RunResult r = merge(dirs, "merged");
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(readBytes(dir_ / "merged" / "oracle.exr") ==
                readBytes(fs::path(whole) / "oracle.exr"));
    // The cost curve with pixels stopping early, its penumbra means, the uniform equivalent.
    expectStatsMatch(readJson(dir_ / "merged" / "oracle.json"),
                     readJson(fs::path(whole) / "oracle.json"));
}

TEST_F(TraceTile, TileHoldsItsRowsAsADataWindow) {
    const std::string t = trace("t2", "2/3");
    const so::ExrFile exr = so::readExrFile((fs::path(t) / "oracle.exr").string());
    EXPECT_EQ(exr.fullWidth, 64);
    EXPECT_EQ(exr.rows.fullHeight, 46);
    EXPECT_EQ(exr.rows.rowBegin, 32);
    EXPECT_EQ(exr.image.height(), 14);
    const nlohmann::json j = readJson(fs::path(t) / "oracle.json");
    EXPECT_EQ(j["tile"]["index"], 2);
    EXPECT_EQ(j["tile"]["count"], 3);
    EXPECT_EQ(j["tile"]["rows"], nlohmann::json::array({32, 46}));
    EXPECT_EQ(j["image"]["height"], 46);
}

TEST_F(TraceTile, BadTileStringsExitTwoNamingTheOption) {
    for (const char* tile : {"3/2", "a/b", "0/0", "-1/4", "1", "1/", "/4", "0/4097", "2/2", "1/4x",
                             "0/13"})  // 13 bands: more than the 12 rows of tiles
        expectInputError(run("trace " + kScene + " --out " + (dir_ / "bad").string() + kOptions +
                             " --tile " + tile),
                         "--tile");
    expectInputError(run("trace " + kScene + " --out " + (dir_ / "bad").string() + kOptions +
                         " --tile 0/2 --verify 10"),
                     "--tile");
}

TEST_F(TraceTile, MergeRefusesTilesThatDoNotBelongTogether) {
    const std::string t0 = trace("t0", "0/3"), t1 = trace("t1", "1/3"), t2 = trace("t2", "2/3");
    expectInputError(merge({t0, t2}, "m"), "tile.count");  // band 1 missing
    expectInputError(merge({t0, t1, t1, t2}, "m"), "tile.index");
    expectInputError(merge({t0, t1, trace("seed", "2/3", " --seed 7")}, "m"), "tile.options.seed");
    expectInputError(merge({t0, t1, trace("split", "2/4")}, "m"), "tile.count");
    const std::string other =
        trace("other", "2/3", "", std::string(SO_SCENES_DIR) + "/penumbra_square.scene.json");
    const RunResult r = merge({t0, t1, other}, "m");
    expectInputError(r, "scene.hash");
    EXPECT_NE(r.stderrText.find("other"), std::string::npos) << r.stderrText;  // the folder
    // A whole trace is not a tile.
    expectInputError(merge({t0, t1, trace("whole")}, "m"), "tile");
    expectInputError(merge({t0, t1, (dir_ / "nowhere").string()}, "m"), "nowhere");
}

}  // namespace
