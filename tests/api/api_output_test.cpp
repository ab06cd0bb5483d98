// The API's write functions (writeTraceOutput, writeRenderOutput, writeCompareOutput) against the
// command line, through the shared library a user links: the same inputs give the same files,
// byte for byte for every EXR, PNG and CSV, and for the JSON files equal once the keys that measure
// the run (times) are taken out; and the commands that read those folders (`gate`, `index`) read
// the API's as they read the command's.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <shadow_oracle/shadow_oracle.h>

#include "tests/support/cli_run.h"

namespace soa = shadow_oracle;
namespace cli = so::test;
namespace fs = std::filesystem;

namespace {

const std::string kScene = std::string(SO_SCENES_DIR) + "/contact_box.scene.json";

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("so_api_output_" + name);
    fs::remove_all(dir);
    return dir;
}

// The JSON without what measures the run: every key naming seconds, milliseconds or a rate per
// second, and the whole process's clock. What is left (counts, options, statistics, provenance)
// must be equal.
nlohmann::json withoutTimes(nlohmann::json j) {
    if (j.is_array())
        for (nlohmann::json& e : j) e = withoutTimes(e);
    if (!j.is_object()) return j;
    nlohmann::json out = nlohmann::json::object();
    for (auto& [key, value] : j.items()) {
        const bool time = key.find("seconds") != std::string::npos ||
                          key.find("per_second") != std::string::npos ||
                          key.find("_ms") != std::string::npos || key == "ms" || key == "timings" ||
                          key == "process";
        if (!time) out[key] = withoutTimes(value);
    }
    return out;
}

bool isTime(const std::string& name) {
    return name.find("seconds") != std::string::npos || name.find("_ms") != std::string::npos;
}

std::vector<std::string> splitCsv(const std::string& line) {
    std::vector<std::string> cells(1);
    for (char c : line) {
        if (c == ',')
            cells.emplace_back();
        else
            cells.back().push_back(c);
    }
    return cells;
}

// A CSV of compare's (no quoted commas in this test's cells) without its time rows (the long
// form: a row per metric) and time columns (the wide form: a column per metric).
std::vector<std::vector<std::string>> csvWithoutTimes(const fs::path& p) {
    std::istringstream in(cli::readBytes(p));
    std::vector<std::vector<std::string>> rows;
    std::vector<bool> keep;
    for (std::string line; std::getline(in, line);) {
        const std::vector<std::string> cells = splitCsv(line);
        if (keep.empty())
            for (const std::string& c : cells) keep.push_back(!isTime(c));
        std::vector<std::string> kept;
        bool timeRow = false;
        for (size_t i = 0; i < cells.size(); ++i) {
            if (i >= keep.size() || keep[i]) kept.push_back(cells[i]);
            timeRow = timeRow || (cells.size() > 4 && i == 4 && isTime(cells[i]));
        }
        if (!timeRow) rows.push_back(kept);
    }
    EXPECT_GT(rows.size(), 1u) << p;
    return rows;
}

nlohmann::json readJson(const fs::path& p) {
    return nlohmann::json::parse(cli::readBytes(p));
}

void expectSameBytes(const fs::path& a, const fs::path& b) {
    ASSERT_TRUE(fs::exists(a)) << a;
    ASSERT_TRUE(fs::exists(b)) << b;
    EXPECT_TRUE(cli::readBytes(a) == cli::readBytes(b)) << a << " and " << b;
}

bool glUnavailable(const soa::Error& e) {
    const std::string why = e.what();
    return why.find("EGL") != std::string::npos || why.find("OpenGL 4.5") != std::string::npos;
}

TEST(ApiOutput, TraceFolderIsTheCommands) {
    const fs::path cli = freshDir("trace_cli"), api = freshDir("trace_api");
    const auto r =
        cli::run("trace " + kScene + " --width 96 --height 64 --quiet --out " + cli.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const soa::Scene scene = soa::Scene::load(kScene);
    soa::TraceOptions t;
    t.width = 96;
    t.height = 64;
    const std::vector<std::string> written =
        soa::writeTraceOutput(scene, soa::trace(scene, t), api.string());
    EXPECT_EQ(written.size(), 2 + scene.lights().size());
    expectSameBytes(cli / "oracle.exr", api / "oracle.exr");
    for (const soa::LightInfo& l : scene.lights())
        expectSameBytes(cli / (l.name + ".png"), api / (l.name + ".png"));
    const nlohmann::json a = readJson(api / "oracle.json"), c = readJson(cli / "oracle.json");
    EXPECT_EQ(withoutTimes(a), withoutTimes(c));
    EXPECT_TRUE(a["phases_seconds"].contains("write_exr"));  // the times are there, measured
    EXPECT_EQ(a["scene"]["file"], kScene);

    // Without previews: no PNG, and oracle.json says no PNG library was used.
    const fs::path bare = freshDir("trace_bare");
    soa::writeTraceOutput(scene, soa::trace(scene, t), bare.string(), /*previews=*/false);
    EXPECT_FALSE(fs::exists(bare / (scene.lights()[0].name + ".png")));
    EXPECT_TRUE(readJson(bare / "oracle.json")["libraries"]["png"].is_null());
}

// An animated scene's frame through the API (Scene::atFrame) is the command's `trace --frame`:
// the same oracle.exr byte for byte and the same oracle.json, sequence_frame included; a frame
// outside the sequence, or a scene without one, is an Error naming "frame".
TEST(ApiOutput, FrameOfASequenceIsTraceFrame) {
    const std::string anim = std::string(SO_SCENES_DIR) + "/sliding_box/sliding_box.scene.json";
    const soa::Scene scene = soa::Scene::load(anim);
    ASSERT_EQ(scene.frames(), 16);
    EXPECT_EQ(scene.fps(), 30.0);
    const fs::path cli = freshDir("frame_cli"), api = freshDir("frame_api");
    const auto r = cli::run("trace " + anim + " --frame 9 --width 64 --height 48 --quiet --out " +
                            cli.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    soa::TraceOptions t;
    t.width = 64;
    t.height = 48;
    const soa::Scene frame9 = scene.atFrame(9);
    EXPECT_NE(frame9.hash(), scene.hash());
    soa::writeTraceOutput(frame9, soa::trace(frame9, t), api.string());
    expectSameBytes(cli / "oracle.exr", api / "oracle.exr");
    const nlohmann::json a = readJson(api / "oracle.json"), c = readJson(cli / "oracle.json");
    EXPECT_EQ(withoutTimes(a), withoutTimes(c));
    EXPECT_EQ(a["sequence_frame"]["index"], 9);
    // Frame 0 is another pose: the check above can fail.
    const fs::path api0 = freshDir("frame_api0");
    soa::writeTraceOutput(scene.atFrame(0), soa::trace(scene.atFrame(0), t), api0.string());
    EXPECT_NE(cli::readBytes(api0 / "oracle.exr"), cli::readBytes(api / "oracle.exr"));
    for (int bad : {-1, 16}) {
        try {
            scene.atFrame(bad);
            ADD_FAILURE() << "frame " << bad << " was accepted";
        } catch (const soa::Error& e) {
            EXPECT_NE(std::string(e.what()).find(": frame: "), std::string::npos) << e.what();
        }
    }
    const soa::Scene still = soa::Scene::load(kScene);
    EXPECT_EQ(still.frames(), 0);
    EXPECT_THROW(still.atFrame(0), soa::Error);
}

// A renderer's image judged by the command (--image) and by the API (in memory): the same folder.
// No GL: images alone need none. Then gate and index read the API's folder as the command's.
TEST(ApiOutput, CompareFolderIsTheCommandsAndGateAndIndexReadIt) {
    const fs::path root = freshDir("compare");
    const fs::path cli = root / "cli", api = root / "api";
    fs::create_directories(root);
    const soa::Scene scene = soa::Scene::load(kScene);
    soa::TraceOptions t;
    t.width = 96;
    t.height = 64;
    const soa::TraceResult oracle = soa::trace(scene, t);
    // The oracle's V moved right by 2 pixels: an error every metric sees.
    soa::Image mine;
    mine.width = 96;
    mine.height = 64;
    for (const soa::LightInfo& l : scene.lights()) {
        const std::vector<float>& v = oracle.image.channel(l.name + ".V");
        std::vector<float>& out = mine.add(l.name + ".V");
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 96; ++x) out[y * 96 + x] = v[y * 96 + std::max(x - 2, 0)];
    }
    const std::string image = (root / "mine.exr").string();
    soa::writeExr(image, mine);
    const auto r = cli::run("compare " + kScene + " --width 96 --height 64 --no-cache " +
                            "--image mine=" + image + " --out " + cli.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;

    soa::CompareOptions c;
    c.images.push_back(soa::readImage(scene, "mine", image, 96, 64));
    const soa::CompareResult result = soa::compare(scene, oracle, c);
    const std::vector<std::string> written =
        soa::writeCompareOutput(scene, oracle, result, api.string());
    EXPECT_EQ(written.back(), (api / "report.html").string());

    for (const char* f : {"error_mine.exr", "mine/raster.exr", "mine/raster.json", "oracle.exr"})
        expectSameBytes(cli / f, api / f);
    // The CSVs hold the oracle's trace time (cost.oracle_seconds): equal without it.
    EXPECT_EQ(csvWithoutTimes(cli / "metrics.csv"), csvWithoutTimes(api / "metrics.csv"));
    EXPECT_EQ(csvWithoutTimes(cli / "metrics_wide.csv"), csvWithoutTimes(api / "metrics_wide.csv"));
    nlohmann::json a = withoutTimes(readJson(api / "metrics.json")),
                   b = withoutTimes(readJson(cli / "metrics.json"));
    // The oracle's key: the cache's key on the command line (--no-cache still computes it), the
    // trace's own through the API, which has no cache.
    EXPECT_EQ(a["oracle"]["key"], "traced");
    a["oracle"].erase("key");
    b["oracle"].erase("key");
    EXPECT_EQ(a, b);
    EXPECT_EQ(nlohmann::json::parse(result.metricsJson), readJson(api / "metrics.json"));

    // gate: the same verdict on both folders' metrics.json, and none of the API's worse than the
    // command's (the command's as the baseline).
    const std::string limits = " --limits " + std::string(SO_SCENES_DIR) + "/limits.json";
    const auto gateCli = cli::run("gate " + (cli / "metrics.json").string() + limits);
    const auto gateApi = cli::run("gate " + (api / "metrics.json").string() + limits);
    EXPECT_NE(gateApi.exitCode, 2) << gateApi.stderrText;  // 2: the file was refused
    EXPECT_EQ(gateApi.exitCode, gateCli.exitCode);
    EXPECT_EQ(gateApi.stdoutText, gateCli.stdoutText);
    EXPECT_NE(gateApi.stdoutText.find(" passed"), std::string::npos) << gateApi.stdoutText;
    const auto baseline = cli::run("gate " + (api / "metrics.json").string() + " --baseline " +
                                   (cli / "metrics.json").string());
    EXPECT_EQ(baseline.exitCode, 0) << baseline.stdoutText << baseline.stderrText;
    // index: one page over both folders.
    const auto index = cli::run("index " + cli.string() + " " + api.string() + " --out " +
                                (root / "index.html").string());
    EXPECT_EQ(index.exitCode, 0) << index.stderrText;
    EXPECT_GT(fs::file_size(root / "index.html"), 0u);
}

TEST(ApiOutput, RenderFolderIsTheCommands) {
    const fs::path cli = freshDir("raster_cli"), api = freshDir("raster_api");
    const soa::Scene scene = soa::Scene::load(kScene);
    soa::RenderOptions o;
    o.width = 64;
    o.height = 48;
    o.frames = 1;
    o.warmup = 0;
    soa::RenderResult render;
    try {
        render = soa::render(scene, "pcf", {{"kernel", "3"}}, o);
    } catch (const soa::Error& e) {
        if (glUnavailable(e)) GTEST_SKIP() << e.what();
        throw;
    }
    soa::writeRenderOutput(scene, render, api.string());
    const auto r = cli::run("raster " + kScene + " --technique pcf --set kernel=3 " +
                            "--width 64 --height 48 --frames 1 --out " + cli.string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    expectSameBytes(cli / "raster.exr", api / "raster.exr");
    for (const soa::LightInfo& l : scene.lights())
        expectSameBytes(cli / (l.name + ".png"), api / (l.name + ".png"));
    EXPECT_EQ(withoutTimes(readJson(api / "raster.json")),
              withoutTimes(readJson(cli / "raster.json")));
}

TEST(ApiOutput, ResultsNotMadeByTheApiAndUnwritableFoldersAreOneLineErrors) {
    const soa::Scene scene = soa::Scene::load(kScene);
    try {
        soa::writeTraceOutput(scene, soa::TraceResult{}, freshDir("empty").string());
        FAIL() << "an empty result was written";
    } catch (const soa::Error& e) {
        EXPECT_EQ(std::string(e.what()), "writeTraceOutput: result: not a result of trace()");
    }
    soa::TraceOptions t;
    t.width = 16;
    t.height = 16;
    const soa::TraceResult oracle = soa::trace(scene, t);
    const fs::path file = freshDir("a_file");
    std::ofstream(file) << "a file where the folder would go\n";
    try {
        soa::writeTraceOutput(scene, oracle, (file / "out").string());
        FAIL() << "wrote under a file";
    } catch (const soa::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find((file / "out").string() + ": cannot create the folder"),
                  std::string::npos)
            << what;
        EXPECT_EQ(what.find('\n'), std::string::npos);
    }
}

}  // namespace
