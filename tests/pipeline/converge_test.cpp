// Cold and converged, both said (issue 64; labels pipeline and gl): a technique that builds over
// frames says how many built its row (metrics.json's history_frames, 0 for a single frame),
// `compare --converge N` renders N still frames and judges the last, and the option's bounds and
// exclusions are one-line errors. The scene: scenes/penumbra_square's square under a rect light,
// small.
#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "compare_run.h"
#include "core/error.h"
#include "gl_test_context.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/pipeline/compare_scene.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kScene = fs::path(SO_SCENES_DIR) / "penumbra_square.scene.json";
const std::string kTemporal = "pcf:temporal=on";

CompareOptions options(const std::vector<std::string>& techniques, int converge,
                       const fs::path& cache) {
    CompareOptions o = quickCompareOptions(kScene, techniques);
    o.convergeFrames = converge;
    o.useCache = true;
    o.cacheDir = cache;  // the cold and the converged run share the oracle
    o.oracle.width = o.raster.width = 96;
    o.oracle.height = o.raster.height = 72;
    return o;
}

std::map<std::string, json> rowsByLabel(const json& metrics) {
    std::map<std::string, json> rows;
    for (const json& r : metrics["results"]) rows[r["label"]] = r;
    return rows;
}

fs::path tempDir(const std::string& name) {
    return fs::temp_directory_path() / ("so_converge_" + name + "_" + std::to_string(::getpid()));
}

TEST(Converge, WhatBuildsOverFramesIsTheHistoryOrTheDenoisersOwn) {
    EXPECT_TRUE(createTechnique("pcf", {"temporal=on"})->buildsOverFrames());
    EXPECT_FALSE(createTechnique("pcf", {})->buildsOverFrames());
    EXPECT_TRUE(createTechnique("pcss", {"temporal=on"})->buildsOverFrames());
    EXPECT_FALSE(createTechnique("raytraced", {"denoiser=none"})->buildsOverFrames());
    for (const char* d : {"temporal", "svgf", "ffx", "hitdist", "rtg"})
        EXPECT_TRUE(
            createTechnique("raytraced", {std::string("denoiser=") + d})->buildsOverFrames())
            << d;
}

TEST(Converge, ASingleFrameIsAColdStartAndSaysSo) {
    REQUIRE_GL();
    const fs::path dir = tempDir("cold");
    CompareOptions o = options({kTemporal, "pcf"}, 0, dir / "cache");
    o.outDir = (dir / "out").string();
    o.embedImages = true;
    const std::map<std::string, json> rows = rowsByLabel(compareMetrics(o));
    EXPECT_EQ(rows.at(kTemporal).at("history_frames"), 0);
    EXPECT_FALSE(rows.at("pcf").contains("history_frames")) << "nothing to build over frames";
    std::ifstream page(dir / "out" / "report.html");
    const std::string html(std::istreambuf_iterator<char>(page), {});
    EXPECT_NE(html.find("cold start (no history)"), std::string::npos);
    std::ifstream wide(dir / "out" / "metrics_wide.csv");
    std::string header;
    std::getline(wide, header);
    EXPECT_NE(header.find("history_frames"), std::string::npos) << header;
    fs::remove_all(dir);
}

// 16 Poisson taps over a filter about as wide as the panel's penumbra (15 texels of a 128-texel
// map): one frame's taps leave noise in the penumbra that eight turned frames average out. (With
// the defaults, 3 x 3 taps of a 2048 map, the penumbra's error is the filter's width, which no
// number of frames changes: 0.22347 cold, 0.22351 after 8 frames at 160 x 120.)
const std::string kWideFew = "pcf:temporal=on,pattern=poisson,kernel=15,resolution=128";

TEST(Converge, EightStillFramesResolveThePenumbraBetterThanOne) {
    REQUIRE_GL();
    const fs::path dir = tempDir("eight");
    const json cold = compareMetrics(options({kWideFew}, 0, dir / "cache"));
    const json warm = compareMetrics(options({kWideFew, kTemporal, "pcf"}, 8, dir / "cache"));
    EXPECT_EQ(warm["options"]["converge_frames"], 8);
    EXPECT_FALSE(warm["options"].contains("sequence_frames"));
    const std::map<std::string, json> rows = rowsByLabel(warm);
    EXPECT_EQ(rows.at(kTemporal).at("history_frames"), 8);
    const json& converged = rows.at(kWideFew);
    EXPECT_EQ(converged.at("history_frames"), 8);
    EXPECT_FALSE(rows.at("pcf").contains("history_frames"));
    // The still frames' own sequence metrics: 8 frames, the row judging the last.
    const json& panel = converged["lights"]["panel"];
    EXPECT_EQ(panel["sequence"]["frames"], 8);
    EXPECT_EQ(panel["mae"].get<double>(), panel["sequence"]["mae_last"].get<double>());
    const double coldMae = cold["results"][0]["lights"]["panel"]["penumbra_mae"];
    const double warmMae = panel["penumbra_mae"];
    EXPECT_LT(warmMae, coldMae) << "cold " << coldMae << ", converged " << warmMae;
    // Without jitter nothing turns: pcf's eight still frames are its one frame.
    const json& still = rows.at("pcf")["lights"]["panel"]["sequence"];
    EXPECT_EQ(still["flickering_pairs"], 0) << still;
    fs::remove_all(dir);
}

TEST(Converge, OneFrameIsTheSingleFrameCompare) {
    REQUIRE_GL();
    const fs::path dir = tempDir("one");
    const json single = compareMetrics(options({kTemporal}, 0, dir / "cache"));
    const json one = compareMetrics(options({kTemporal}, 1, dir / "cache"));
    const json &a = single["results"][0], &b = one["results"][0];
    EXPECT_EQ(b.at("history_frames"), 0) << "one frame holds no history";
    EXPECT_EQ(a["lights"]["panel"]["mae"], b["lights"]["panel"]["mae"]);
    EXPECT_EQ(a["lights"]["panel"]["penumbra_mae"], b["lights"]["panel"]["penumbra_mae"]);
    fs::remove_all(dir);
}

TEST(Converge, OutOfBoundsOrWithAnotherTimeIsAOneLineError) {
    const fs::path out = tempDir("errors");
    const std::string compare = "compare " + kScene.string() + " --technique " + kTemporal +
                                " --width 32 --height 24 --out " + out.string();
    std::string log;
    // The range is checked as every table option's is (CLI11's line, then its --help hint).
    for (const char* n : {"0", "1000", "-1"}) {
        EXPECT_NE(runMerged(compare + " --converge " + n, &log), 0) << n;
        EXPECT_EQ(log.substr(0, log.find('\n')),
                  "--converge: Value " + std::string(n) + " not in range 1 to 256")
            << log;
    }
    for (const char* other : {"--sequence", "--frames-path 3"}) {
        EXPECT_NE(runMerged(compare + " --converge 4 " + other, &log), 0) << other;
        EXPECT_NE(log.find("--converge"), std::string::npos) << log;
        EXPECT_NE(log.find(std::string(other).substr(0, std::string(other).find(' '))),
                  std::string::npos)
            << log;
    }
    EXPECT_FALSE(fs::exists(out)) << "refused before any work";
    // Where no command line checks the exclusions (a sweep's task, the library): the same rule,
    // naming both.
    CompareOptions o = options({kTemporal}, 4, out / "cache");
    o.sequence = true;
    try {
        compareScene(o);
        ADD_FAILURE() << "converge with a sequence ran";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("converge"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("sequence"), std::string::npos) << e.what();
    }
    // The sweep spec's value is checked by the table: 0 and 257 are out of range there too.
    for (double n : {0.0, 257.0}) {
        CompareOptions s;
        EXPECT_THROW(
            applyCompareOptions({{"converge", {n, ""}}}, {"spec.json", false, "", false}, s),
            InputError)
            << n;
    }
}

}  // namespace
}  // namespace so
