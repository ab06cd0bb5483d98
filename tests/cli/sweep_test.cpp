// The sweep end to end on this machine (label gl): `sweep --jobs 2` over two scenes, resumed after
// lost rows, a failed oracle reported with its log and retried, a killed run, and a task's row
// against a plain `compare` of the same setting (the merged table has compare's numbers).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "gl_test_context.h"
#include "sweep_test_util.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;

// Two shipped scenes copied beside the spec (so a test can break one), and a 2 x 2 grid of
// slope-bias settings: 8 tasks.
struct SweepFixture {
    fs::path dir, spec, brokenScene, out;
    explicit SweepFixture(const std::string& name) {
        dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir / "scenes");
        fs::copy(fs::path(SO_SCENES_DIR) / "meshes", dir / "scenes" / "meshes",
                 fs::copy_options::recursive);
        for (const char* s : {"contact_box.scene.json", "spot_objects.scene.json"})
            fs::copy_file(fs::path(SO_SCENES_DIR) / s, dir / "scenes" / s);
        brokenScene = dir / "scenes" / "spot_objects.scene.json";
        spec = dir / "spec.json";
        std::ofstream(spec)
            << R"({"sweep_format": 1, "name": "t", "scenes": ["scenes/*.scene.json"],
            "width": 64, "height": 48, "frames": 1,
            "techniques": [{"name": "slope-bias", "params": {"alpha": [0, 2], "min": [0, 0.5],
                                                             "resolution": 512}}]})";
        out = dir / "out";
    }
    ~SweepFixture() { fs::remove_all(dir); }
    int sweep(std::string* log, const std::string& extra = "--jobs 2 --quiet") const {
        return runCli("sweep " + spec.string() + " --out " + out.string() + " " + extra, log);
    }
    size_t rows() const {
        size_t n = 0;
        for (const auto& e : fs::directory_iterator(out / "rows"))
            n += e.path().extension() == ".json";
        return n;
    }
};

TEST(Sweep, RunsLocallyAndMergesCompareNumbers) {
    REQUIRE_GL();
    const SweepFixture f("so_sweep_local");
    std::string log;
    ASSERT_EQ(f.sweep(&log), 0) << log;
    EXPECT_NE(log.find("merged 8 of 8 tasks"), std::string::npos) << log;
    EXPECT_EQ(f.rows(), 8u);
    const auto merged = mergedResults(f.out);
    ASSERT_EQ(merged.size(), 8u);
    // The swept parameters are columns of the long table; the fixed one is not.
    const std::string csv = readBytes(f.out / "metrics.csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "scene,light,technique,label,metric,value,task,param.alpha,param.min");
    EXPECT_NE(readBytes(f.out / "metrics_wide.csv").find("param.resolution"), std::string::npos);
    EXPECT_NE(readBytes(f.out / "report.html").find("8 of 8 tasks"), std::string::npos);

    // One task against compare of the same setting with the sweep's oracle: the same metrics.
    std::ifstream in(f.out / "metrics.json");
    const nlohmann::json all = nlohmann::json::parse(in);
    const nlohmann::json& r = all["results"][5];
    const std::string label = r["label"], id = r["task"]["id"];
    const std::string scene = (f.dir / r["task"]["scene"].get<std::string>()).string();
    ASSERT_EQ(runCli("compare " + scene + " --technique " + label +
                         " --width 64 --height 48 --frames 1 --cache " +
                         (f.out / "oracles").string() + " --out " + (f.dir / "compare").string(),
                     &log),
              0)
        << log;
    EXPECT_NE(log.find("oracle from the cache"), std::string::npos)
        << "the sweep's oracle: " << log;
    std::ifstream cin(f.dir / "compare" / "metrics.json");
    const nlohmann::json compare = nlohmann::json::parse(cin);
    EXPECT_EQ(withoutTimings(compare["results"][0]["lights"]), merged.at(id)["lights"]);
}

TEST(Sweep, ResumesRetriesAndReportsFailuresWithTheirLogs) {
    REQUIRE_GL();
    const SweepFixture f("so_sweep_resume");
    std::string log;
    ASSERT_EQ(f.sweep(&log), 0) << log;
    const auto first = mergedResults(f.out);
    // Two rows lost and the second scene broken: its oracle fails, its tasks do not run, the
    // merge lists them with the oracle's log and the sweep exits 1.
    std::ifstream in(f.out / "metrics.json");
    const nlohmann::json all = nlohmann::json::parse(in);
    std::vector<std::string> spotIds;
    for (const auto& r : all["results"])
        if (r["task"]["scene"].get<std::string>().find("spot") != std::string::npos)
            spotIds.push_back(r["task"]["id"]);
    ASSERT_EQ(spotIds.size(), 4u);
    for (size_t k = 0; k < 2; ++k) fs::remove(f.out / "rows" / (spotIds[k] + ".json"));
    const std::string good = readBytes(f.brokenScene);
    std::ofstream(f.brokenScene) << "{ not json";
    ASSERT_EQ(f.sweep(&log, "--jobs 2"), 1) << log;
    EXPECT_NE(log.find("6 of 8 tasks already finished, 2 to run over 1 scenes"), std::string::npos)
        << log;
    EXPECT_NE(log.find("2 of 8 tasks did not finish"), std::string::npos) << log;
    EXPECT_NE(log.find("its scene's oracle failed"), std::string::npos) << log;
    EXPECT_NE(log.find("logs/oracle-1.log"), std::string::npos) << log;
    std::ifstream jin(f.out / "metrics.json");
    EXPECT_EQ(nlohmann::json::parse(jin)["failed"].size(), 2u);
    // Mended, the rerun runs just those two, with the oracle already present.
    std::ofstream(f.brokenScene) << good;
    ASSERT_EQ(f.sweep(&log), 0) << log;
    EXPECT_EQ(f.rows(), 8u);
    EXPECT_NE(readBytes(f.out / "logs" / "oracle-1.log").find("present"), std::string::npos);
    EXPECT_EQ(mergedResults(f.out), first) << "a resumed sweep has the numbers of a whole one";
    // A finished sweep reruns nothing.
    ASSERT_EQ(f.sweep(&log, "--jobs 2"), 0) << log;
    EXPECT_NE(log.find("8 of 8 tasks already finished, 0 to run"), std::string::npos) << log;
    // A scene edited under the same name: its rows are stale, and sweep-merge says so where the
    // sweep has not run since; the sweep runs them again.
    const fs::path box = f.dir / "scenes" / "contact_box.scene.json";
    nlohmann::json scene = nlohmann::json::parse(readBytes(box));
    scene["lights"][0]["position"][0] = scene["lights"][0]["position"][0].get<double>() + 1.0;
    std::ofstream(box) << scene.dump(1);
    nlohmann::json hashes = nlohmann::json::parse(readBytes(f.out / "scene_hashes.json"));
    const nlohmann::json recorded = hashes;
    hashes["0"] = "0123";
    std::ofstream(f.out / "scene_hashes.json") << hashes.dump();
    EXPECT_EQ(runCli("sweep-merge " + f.out.string(), &log), 1);
    EXPECT_NE(log.find("stale: its scene changed"), std::string::npos) << log;
    std::ofstream(f.out / "scene_hashes.json") << recorded.dump();
    ASSERT_EQ(f.sweep(&log, "--jobs 2"), 0) << log;
    EXPECT_NE(log.find("scenes/contact_box.scene.json changed since its rows were made: 4 rows "
                       "removed"),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("4 of 8 tasks already finished, 4 to run"), std::string::npos) << log;
    EXPECT_NE(mergedResults(f.out), first) << "the moved light changes the box's metrics";
}

TEST(Sweep, AKilledRunLosesOnlyTheTasksInFlight) {
    REQUIRE_GL();
    const SweepFixture f("so_sweep_kill");
    // The sweep in its own process group, killed (SIGKILL, children too) once some rows exist.
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::setpgid(0, 0);
        const std::string cmd = std::string(SO_CLI_PATH) + " sweep " + f.spec.string() + " --out " +
                                f.out.string() + " --jobs 2 --quiet > /dev/null 2>&1";
        ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::setpgid(pid, pid);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline &&
           !(fs::exists(f.out / "rows") && f.rows() >= 2))
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::kill(-pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    const size_t kept = fs::exists(f.out / "rows") ? f.rows() : 0;
    // Every row that exists is whole (written to a temporary file, then renamed).
    for (const auto& e : fs::directory_iterator(f.out / "rows")) {
        if (e.path().extension() != ".json") continue;
        EXPECT_NO_THROW(nlohmann::json::parse(readBytes(e.path()))) << e.path();
    }
    std::string log;
    ASSERT_EQ(f.sweep(&log, "--jobs 2"), 0) << log;
    EXPECT_NE(log.find(std::to_string(kept) + " of 8 tasks already finished"), std::string::npos)
        << log;
    EXPECT_EQ(f.rows(), 8u);
}

TEST(Sweep, ForeignFoldersAndIndicesAreOneLineErrors) {
    REQUIRE_GL();
    const SweepFixture f("so_sweep_errors");
    std::string log;
    ASSERT_EQ(f.sweep(&log), 0) << log;
    // Another spec into the same folder.
    const fs::path other = f.dir / "other.json";
    std::ofstream(other) << R"({"sweep_format": 1, "scenes": ["scenes/contact_box.scene.json"],
        "techniques": [{"name": "basic"}]})";
    EXPECT_EQ(runCli("sweep " + other.string() + " --out " + f.out.string(), &log), 2);
    EXPECT_NE(log.find(other.string() + ": differs from the spec of the sweep in"),
              std::string::npos)
        << log;
    EXPECT_EQ(runCli("sweep-task " + f.out.string() + " --index 8", &log), 2);
    EXPECT_NE(log.find("--index: 8 is out of range: the sweep has 8 tasks"), std::string::npos)
        << log;
    EXPECT_EQ(runCli("sweep-merge " + f.dir.string(), &log), 2);
    EXPECT_NE(log.find((f.dir / "sweep.json").string() + ": missing"), std::string::npos) << log;
    // A task run again is a no-op: its row stays.
    EXPECT_EQ(runCli("sweep-task " + f.out.string() + " --index 3", &log), 0);
    EXPECT_NE(log.find("already finished"), std::string::npos) << log;
}

// keep_outputs: each task's compare folder kept as outputs/<id>/, its metrics.json the row's own
// numbers; without it, a task writes its row and nothing else (no work/ folder is left).
TEST(Sweep, KeepsEachTasksCompareFolderWhenAsked) {
    REQUIRE_GL();
    const fs::path dir =
        fs::temp_directory_path() / ("so_sweep_keep_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const bool keep : {true, false}) {
        const fs::path spec = dir / "spec.json", out = dir / (keep ? "kept" : "dropped");
        std::ofstream(spec)
            << R"({"sweep_format": 1, "scenes": [")" << SO_SCENES_DIR
            << R"(/contact_box.scene.json"], "width": 48, "height": 36,
            "frames": 1, "keep_outputs": )"
            << (keep ? "true" : "false")
            << R"(, "techniques": [{"name": "pcf", "params": {"kernel": [1, 3]}}]})";
        std::string log;
        ASSERT_EQ(runCli("sweep " + spec.string() + " --out " + out.string() + " --quiet", &log), 0)
            << log;
        const auto merged = mergedResults(out);
        ASSERT_EQ(merged.size(), 2u);
        EXPECT_TRUE(!fs::exists(out / "work") || fs::is_empty(out / "work"));
        EXPECT_EQ(fs::exists(out / "outputs"), keep);
        if (!keep) continue;
        for (const auto& [id, result] : merged) {
            const fs::path kept = out / "outputs" / id;
            std::ifstream in(kept / "metrics.json");
            ASSERT_TRUE(in) << kept;
            const nlohmann::json metrics = nlohmann::json::parse(in);
            EXPECT_EQ(withoutTimings(metrics["results"][0]["lights"]), result["lights"]) << id;
            // The row's folder (the label made safe for file names) and its error EXR.
            const std::string label = result["label"], fileLabel = "pcf_kernel_" + label.substr(11);
            EXPECT_EQ(label.substr(0, 11), "pcf:kernel=");
            EXPECT_TRUE(fs::exists(kept / fileLabel / "raster.exr")) << id;
            EXPECT_TRUE(fs::exists(kept / ("error_" + fileLabel + ".exr"))) << id;
        }
    }
    fs::remove_all(dir);
}

// The named channels of `from`, shifted `dx` pixels to the right: a renderer's image whose error
// grows with dx.
void writeShifted(const fs::path& path, const ChannelImage& from, int dx) {
    ChannelImage img(from.width(), from.height());
    for (const char* n : {"cone.V", "fill.V"}) {
        float* dst = img.addChannel(n);
        const float* src = from.channel(n);
        for (int y = 0; y < from.height(); ++y)
            for (int x = 0; x < from.width(); ++x)
                dst[size_t(y) * size_t(from.width()) + size_t(x)] =
                    src[size_t(y) * size_t(from.width()) + size_t(std::max(x - dx, 0))];
    }
    writeExr(path.string(), img);
}

const nlohmann::json& resultOf(const nlohmann::json& metrics, const std::string& label) {
    for (const nlohmann::json& r : metrics.at("results"))
        if (r.at("label") == label) return r;
    ADD_FAILURE() << "no result " << label;
    return metrics.at("results").at(0);
}

// A renderer's settings grid (its images, with cost files) merges with the built-in techniques into
// one table and one Pareto front; an image row has compare --image's numbers; a re-rendered image
// makes its row stale, and the sweep runs that task again.
TEST(Sweep, ARenderersImagesJoinTheBuiltInTechniquesFront) {
    REQUIRE_GL();
    const fs::path dir =
        fs::temp_directory_path() / ("so_sweep_images_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "scenes");
    fs::copy(fs::path(SO_SCENES_DIR) / "meshes", dir / "scenes" / "meshes",
             fs::copy_options::recursive);
    const fs::path scene = dir / "scenes" / "spot_objects.scene.json";  // hard lights cone, fill
    fs::copy_file(fs::path(SO_SCENES_DIR) / "spot_objects.scene.json", scene);
    std::string log;
    ASSERT_EQ(runCli("trace " + scene.string() + " --out " + (dir / "trace").string() +
                         " --width 64 --height 48 --quiet",
                     &log),
              0)
        << log;
    const ChannelImage oracle = readExr((dir / "trace" / "oracle.exr").string());
    const fs::path renders = dir / "renders" / "spot_objects";
    fs::create_directories(renders);
    // Exact but slow, in between, cheap and wrong: the front's two ends are the renderer's.
    const std::vector<std::pair<int, double>> shiftMs = {{0, 1e4}, {2, 1.0}, {4, 1e-3}};
    for (const auto& [shift, ms] : shiftMs) {
        const fs::path image = renders / ("shift_" + std::to_string(shift) + ".exr");
        writeShifted(image, oracle, shift);
        std::ofstream(image.string() + ".json")
            << nlohmann::json{{"renderer", "engine 1.0"}, {"frame_ms", ms}, {"memory_bytes", 4096}};
    }
    const fs::path spec = dir / "spec.json", out = dir / "out";
    std::ofstream(spec) << R"({"sweep_format": 1, "scenes": ["scenes/*.scene.json"],
        "width": 64, "height": 48, "frames": 1,
        "techniques": [{"name": "slope-bias", "params": {"alpha": [0, 2], "resolution": 512}}],
        "images": [{"name": "engine", "path": "renders/{scene}/shift_{shift}.exr",
                    "params": {"shift": [0, 2, 4]}}]})";
    const std::string sweep = "sweep " + spec.string() + " --out " + out.string() + " --jobs 2";
    ASSERT_EQ(runCli(sweep + " --quiet", &log), 0) << log;
    EXPECT_NE(log.find("merged 5 of 5 tasks"), std::string::npos) << log;

    const nlohmann::json merged = nlohmann::json::parse(readBytes(out / "metrics.json"));
    const nlohmann::json& exact = resultOf(merged, "engine:shift=0");
    EXPECT_EQ(exact["source"], "external");
    EXPECT_EQ(exact["renderer"], "engine 1.0");
    EXPECT_EQ(exact["parameters"]["shift"], 0.0) << "the grid's values are the image's parameters";
    for (const char* light : {"cone", "fill"}) {
        EXPECT_EQ(exact["lights"][light]["mae"], 0.0) << light;
        EXPECT_EQ(exact["lights"][light]["cost"]["frame_ms"], 1e4) << light;
        EXPECT_GT(resultOf(merged, "engine:shift=4")["lights"][light]["mae"].get<double>(), 0.0);
    }
    const std::string csv = readBytes(out / "metrics.csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "scene,light,technique,label,metric,value,task,param.alpha,param.shift");
    EXPECT_NE(csv.find(",cone,engine,engine:shift=4,mae,"), std::string::npos);
    // One front over both: the exact image is its most accurate end, the cheap one its cheapest.
    const std::string html = readBytes(out / "report.html");
    const std::string tableStart =
        R"(<table class="front" data-metric="mae" data-cost="cost.frame_ms">)";
    const size_t at = html.find(tableStart);
    ASSERT_NE(at, std::string::npos);
    const std::string front = html.substr(at, html.find("</table>", at) - at);
    EXPECT_NE(front.find(">engine:shift=0<"), std::string::npos) << front;
    EXPECT_NE(front.find(">engine:shift=4<"), std::string::npos) << front;
    EXPECT_NE(html.find("slope-bias"), std::string::npos);

    // The row of shift=2 against compare --image of the same file with the sweep's oracle.
    const fs::path shift2 = renders / "shift_2.exr";
    ASSERT_EQ(runCli("compare " + scene.string() + " --image e=" + shift2.string() +
                         " --width 64 --height 48 --frames 1 --cache " +
                         (out / "oracles").string() + " --out " + (dir / "compare").string(),
                     &log),
              0)
        << log;
    EXPECT_NE(log.find("oracle from the cache"), std::string::npos) << log;
    const nlohmann::json compare =
        nlohmann::json::parse(readBytes(dir / "compare" / "metrics.json"));
    EXPECT_EQ(withoutTimings(compare["results"][0]["lights"]),
              withoutTimings(resultOf(merged, "engine:shift=2")["lights"]));

    // Re-rendered: the merge counts the row stale, the sweep runs that task again.
    writeShifted(shift2, oracle, 3);
    EXPECT_EQ(runCli("sweep-merge " + out.string(), &log), 1);
    EXPECT_NE(log.find("stale: its image changed"), std::string::npos) << log;
    ASSERT_EQ(runCli(sweep, &log), 0) << log;
    EXPECT_NE(log.find("1 images changed since their rows were made"), std::string::npos) << log;
    EXPECT_NE(log.find("4 of 5 tasks already finished, 1 to run"), std::string::npos) << log;
    const nlohmann::json again = nlohmann::json::parse(readBytes(out / "metrics.json"));
    EXPECT_NE(resultOf(again, "engine:shift=2")["lights"]["cone"]["mae"],
              resultOf(merged, "engine:shift=2")["lights"]["cone"]["mae"]);
    // A render gone: the spec no longer plans, one line naming the entry.
    fs::remove(shift2);
    EXPECT_EQ(runCli(sweep, &log), 2);
    EXPECT_NE(log.find("images[0].path: no such image for engine:shift=2"), std::string::npos)
        << log;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so
