// The command line as a user meets it: exit codes, one-line errors, and byte-identical output
// files whatever the thread count.
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;

using so::test::readBytes;
using so::test::run;
using so::test::RunResult;

TEST(Cli, EveryBrokenFileExitsTwoWithOneLine) {
    const fs::path out = fs::temp_directory_path() / "so_cli_broken_out";
    size_t files = 0;
    for (const char* corpus : {"broken_scene", "broken_gltf"}) {
        for (const auto& entry : fs::directory_iterator(fs::path(SO_TEST_DATA_DIR) / corpus)) {
            const std::string ext = entry.path().extension().string();
            const bool sceneFile = std::string(corpus) == "broken_scene"
                                       ? ext == ".json"
                                       : (ext == ".gltf" || ext == ".glb");
            if (!sceneFile) continue;
            ++files;
            RunResult r =
                run("trace '" + entry.path().string() + "' --out " + out.string() + " --quiet");
            EXPECT_EQ(r.exitCode, 2) << entry.path() << ": " << r.stderrText;
            EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1)
                << entry.path() << ": " << r.stderrText;
            // It names the file: the scene itself, or for mesh errors the glTF file it references.
            const bool namesScene = r.stderrText.rfind(entry.path().string() + ": ", 0) == 0;
            const bool namesMesh =
                r.stderrText.rfind(entry.path().parent_path().string() + "/", 0) == 0 &&
                r.stderrText.find(".gltf: ") != std::string::npos;
            EXPECT_TRUE(namesScene || namesMesh) << r.stderrText;
        }
    }
    EXPECT_GT(files, 100u);
}

TEST(Cli, BadArgumentsExitTwo) {
    EXPECT_EQ(run("").exitCode, 2);
    EXPECT_EQ(run("trace").exitCode, 2);
    EXPECT_EQ(run("frobnicate x").exitCode, 2);
    EXPECT_EQ(run("trace " SO_SCENES_DIR "/contact_box.scene.json --out /tmp/x --width 0").exitCode,
              2);
    RunResult missing = run("trace /nonexistent/scene.json --out /tmp/x");
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_EQ(missing.stderrText, "/nonexistent/scene.json: no such file\n");
}

TEST(Cli, RasterBadArgumentsExitTwo) {
    const std::string scene = std::string(SO_SCENES_DIR) + "/contact_box.scene.json";
    RunResult unknown = run("raster " + scene + " --out /tmp/x --technique nope");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.stderrText.find("valid: "), std::string::npos) << unknown.stderrText;
    EXPECT_NE(unknown.stderrText.find("basic"), std::string::npos) << unknown.stderrText;
    RunResult badKey = run("raster " + scene + " --out /tmp/x --technique pcf --set kernal=3");
    EXPECT_EQ(badKey.exitCode, 2);
    EXPECT_NE(badKey.stderrText.find("kernel"), std::string::npos) << badKey.stderrText;
    EXPECT_EQ(run("raster " + scene + " --out /tmp/x --technique pcf --set kernel=99").exitCode, 2);
    EXPECT_EQ(run("raster " + scene + " --out /tmp/x --technique pcf --set kernel=4").exitCode, 2);
    EXPECT_EQ(run("raster /nonexistent.json --out /tmp/x --technique basic").exitCode, 2);
}

// oracle.json without what may differ between runs: times, rates and the thread count.
nlohmann::json withoutTimings(nlohmann::json j) {
    if (j.is_object()) {
        nlohmann::json out = nlohmann::json::object();
        for (auto it = j.begin(); it != j.end(); ++it) {
            const std::string& k = it.key();
            const auto endsWith = [&](const std::string& suffix) {
                return k.size() >= suffix.size() &&
                       k.compare(k.size() - suffix.size(), suffix.size(), suffix) == 0;
            };
            if (endsWith("seconds") || endsWith("_per_second") || k == "threads") continue;
            out[k] = withoutTimings(*it);
        }
        return out;
    }
    if (j.is_array())
        for (auto& e : j) e = withoutTimings(e);
    return j;
}

TEST(Cli, ShippedScenesTraceIdenticallyAtAnyThreadCount) {
    for (const char* name :
         {"contact_box", "spot_objects", "terrain_sun", "penumbra_square", "sphere_light"}) {
        const std::string scene = std::string(SO_SCENES_DIR) + "/" + name + ".scene.json";
        std::string first;
        nlohmann::json firstJson;
        for (int threads : {1, 2, 5}) {
            const fs::path out = fs::temp_directory_path() /
                                 ("so_cli_det_" + std::string(name) + std::to_string(threads));
            RunResult r = run("trace " + scene + " --out " + out.string() +
                              " --width 200 --height 150 --quiet --target-error 0.03 --threads " +
                              std::to_string(threads));
            ASSERT_EQ(r.exitCode, 0) << r.stderrText;
            std::string bytes = readBytes(out / "oracle.exr");
            ASSERT_GT(bytes.size(), 1000u);
            if (first.empty()) first = bytes;
            EXPECT_TRUE(bytes == first)
                << name << ": oracle.exr differs with " << threads << " threads";
            // The JSON is complete and counts every pixel once per light.
            nlohmann::json j = nlohmann::json::parse(readBytes(out / "oracle.json"));
            // Every statistic too (sampling_efficiency was once summed in thread order).
            if (firstJson.is_null()) firstJson = withoutTimings(j);
            EXPECT_EQ(withoutTimings(j), firstJson)
                << name << ": oracle.json differs with " << threads << " threads";
            for (const auto& light : j["lights"]) {
                uint64_t total = light.contains("pixels_sampled")
                                     ? light["pixels_sampled"].get<uint64_t>()
                                     : light["rays_traced"].get<uint64_t>();
                for (const auto& [reason, count] : light["rays_skipped"].items())
                    total += count.get<uint64_t>();
                // Where auto chose exact, the exact pass gave every pixel the camera hit (both
                // views are filled by geometry) but those it left to the sampled pass.
                const nlohmann::json& exact = light.value("exact_penumbra", nlohmann::json());
                if (exact.is_object() && exact["method"] == "exact")
                    total += exact["pixels_exact"].get<uint64_t>();
                EXPECT_EQ(total, 200u * 150u) << name;
                EXPECT_TRUE(fs::exists(out / (light["name"].get<std::string>() + ".png")));
            }
        }
    }
}

}  // namespace

namespace {

std::string runStdout(const std::string& args) {
    const fs::path outFile =
        fs::temp_directory_path() / ("so_cli_test_" + std::to_string(::getpid()) + ".out");
    const std::string cmd = std::string(SO_CLI_PATH) + " " + args + " > " + outFile.string();
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::string text = readBytes(outFile);
    fs::remove(outFile);
    return text;
}

// docs/techniques.md's tables are generated from the techniques' parameter tables: the document
// must say exactly what the code validates.
TEST(Docs, TechniqueTablesMatchTheCode) {
    const std::string doc = readBytes(fs::path(SO_DOCS_DIR) / "techniques.md");
    const std::string begin = "<!-- BEGIN techniques (generated: scripts/update-docs) -->\n\n",
                      end = "<!-- END techniques -->";
    const size_t a = doc.find(begin), b = doc.find(end);
    ASSERT_NE(a, std::string::npos);
    ASSERT_NE(b, std::string::npos);
    EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()),
              runStdout("techniques --markdown"))
        << "docs/techniques.md is stale: run scripts/update-docs";
}

// The listing as JSON: every technique with its parameters, ranges and defaults.
TEST(Cli, TechniquesListingAsJson) {
    const nlohmann::json j = nlohmann::json::parse(runStdout("techniques --json"));
    EXPECT_EQ(j["format_version"], 7);
    EXPECT_TRUE(j["axes"].contains("denoiser"));
    std::vector<std::string> names;
    for (const auto& t : j["techniques"]) {
        names.push_back(t["name"]);
        EXPECT_FALSE(t["summary"].get<std::string>().empty());
        for (const auto& p : t["parameters"]) {
            EXPECT_LE(p["min"].get<double>(), p["default"].get<double>()) << t["name"] << p;
            EXPECT_LE(p["default"].get<double>(), p["max"].get<double>()) << t["name"] << p;
            if (p.value("max_exclusive", false)) {
                EXPECT_LT(p["default"].get<double>(), p["max"].get<double>()) << t["name"] << p;
            }
        }
    }
    for (const char* name : {"basic", "pcf", "vsm", "evsm", "hw-pcf"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

}  // namespace
