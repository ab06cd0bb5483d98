// Blender as an external renderer, end to end (label "external", issue 29): `shadow-oracle view`,
// examples/blender/render_shadows.py under Blender's Cycles and EEVEE, then the images against the
// oracle two ways: read here with the project's EXR reader against `trace`'s oracle.exr, and
// through `compare --image` (metrics_wide.csv). Skips, saying why, where Blender is missing or its
// glTF importer cannot run; the EEVEE test alone skips where no OpenGL context opens (surfaceless
// EGL, then xvfb-run). 96x72 images, 2 threads: about 40 s on 2 cores, so ctest runs the binary
// once (every render is shared by the tests in one process).
//
// Expected figures (docs/external.md, "Blender: EEVEE and Cycles end to end"):
// - hard lights (spot_objects: a spot and a point light), Cycles: the same pixels as the oracle
//   except a pixel or two whose centre ray grazes an edge: mae below 0.01.
// - an area light (penumbra_square's rect), Cycles at N spp: V is the ratio of two renders with
//   the same light samples, so per pixel it is an estimate of V from N samples. Independent
//   samples give E|error| = sqrt(2/pi) sqrt(V (1 - V) / N) (the mean absolute value of a normal
//   error); with the oracle's own error, sqrt(2/pi) sqrt(V (1 - V) / N + stderr^2). Cycles' samples
//   are stratified (low-discrepancy), which does no worse, so the mean of that over the penumbra's
//   pixels bounds Cycles' penumbra MAE (measured at 0.17 of it at 64 spp).
// - EEVEE's shadow maps: above Cycles on both scenes; soft shadows off (hard edges under an area
//   light) above soft shadows on.
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "core/image.h"
#include "shell_run.h"

namespace so {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::quote;
using test::shell;
using test::Shell;

constexpr int kWidth = 96, kHeight = 72;
constexpr int kCyclesHardSpp = 16, kCyclesAreaSpp = 64, kEeveeSamples = 16;

std::string lastLine(const std::string& text) {
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last;
}

std::string errorLine(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        if (line.find("render_shadows.py: error") != std::string::npos) return line;
    return lastLine(text);
}

fs::path workDir() {
    return fs::path(SO_BINARY_DIR) / "blender_external";
}
fs::path script() {
    return fs::path(SO_SOURCE_DIR) / "examples/blender/render_shadows.py";
}
fs::path scene(const std::string& name) {
    return fs::path(SO_SCENES_DIR) / (name + ".scene.json");
}

// Blender's path, or empty with why.
std::string findBlender(std::string& why) {
    if (const char* b = std::getenv("BLENDER"); b && *b) return b;
    const Shell s = shell("command -v blender");
    if (s.rc != 0 || s.out.empty()) {
        why = "no blender on PATH (Debian: apt-get install blender python3-numpy; or set BLENDER)";
        return "";
    }
    return lastLine(s.out);
}

// view.json from `shadow-oracle view`; empty, with its last error line in `why`, where it fails.
fs::path makeView(const std::string& name, std::string& why) {
    const fs::path dir = workDir() / name / "view";
    fs::remove_all(dir);
    const test::RunResult r =
        test::run("view " + quote(scene(name).string()) + " --out " + quote(dir.string()) +
                  " --width " + std::to_string(kWidth) + " --height " + std::to_string(kHeight));
    if (r.exitCode == 0 && fs::exists(dir / "view.json")) return dir / "view.json";
    why = lastLine(r.stderrText);
    return {};
}

// One render_shadows.py run; the shadows.exr path, or empty with Blender's error line in why.
std::string render(const std::string& launcher, const fs::path& view, const std::string& label,
                   const std::string& args, std::string& why, int* rc = nullptr) {
    const fs::path out = view.parent_path().parent_path() / label;
    fs::remove_all(out);
    const Shell s = shell(launcher + " -b --factory-startup --python-exit-code 1 -P " +
                          quote(script().string()) + " -- " + quote(view.string()) + " --out " +
                          quote(out.string()) + " --threads 2 " + args);
    if (rc) *rc = s.rc;
    std::ofstream(out.string() + ".log") << s.out;
    if (s.rc != 0 || !fs::exists(out / "shadows.exr")) {
        why = errorLine(s.out);
        return "";
    }
    return (out / "shadows.exr").string();
}

struct Renders {
    std::string skip;  // why everything skips
    std::string eeveeSkip;
    std::map<std::string, std::string> exr;  // "scene/label" -> shadows.exr
    std::map<std::string, fs::path> view, oracle;
};

// Everything once, in the first test that needs it.
const Renders& renders() {
    static const Renders all = [] {
        Renders r;
        const std::string blender = findBlender(r.skip);
        if (blender.empty()) return r;
        for (const std::string name : {"spot_objects", "penumbra_square"}) {
            std::string why;
            r.view[name] = makeView(name, why);
            if (r.view[name].empty()) {  // this project's failure, not a missing Blender
                r.skip = "shadow-oracle view failed: " + why + " (FAIL)";
                return r;
            }
            const fs::path odir = workDir() / name / "oracle";
            const test::RunResult t = test::run(
                "trace " + quote(scene(name).string()) + " --out " + quote(odir.string()) +
                " --width " + std::to_string(kWidth) + " --height " + std::to_string(kHeight) +
                " --target-error 0.002 --threads 2 --quiet");
            if (t.exitCode != 0) {
                r.skip = "trace failed: " + lastLine(t.stderrText) + " (FAIL)";
                return r;
            }
            r.oracle[name] = odir / "oracle.exr";
        }
        std::string why;
        int rc = 0;
        const std::string q = quote(blender);
        r.exr["spot_objects/cycles"] =
            render(q, r.view["spot_objects"], "cycles",
                   "--engine cycles --samples " + std::to_string(kCyclesHardSpp), why, &rc);
        if (r.exr["spot_objects/cycles"].empty()) {
            // Exit 3: Blender runs but its glTF importer cannot (no numpy): not this project's.
            r.skip = (rc == 3 ? "" : "Cycles failed: ") + why;
            if (rc != 3) r.skip += " (FAIL)";
            return r;
        }
        r.exr["penumbra_square/cycles"] =
            render(q, r.view["penumbra_square"], "cycles",
                   "--engine cycles --samples " + std::to_string(kCyclesAreaSpp), why);
        // EEVEE: surfaceless EGL with -b, else under xvfb-run.
        const std::string eevee = "--engine eevee --samples " + std::to_string(kEeveeSamples);
        std::string launcher = q;
        std::string exr = render(launcher, r.view["spot_objects"], "eevee-soft",
                                 eevee + " --eevee-soft-shadows on", why);
        if (exr.empty() && shell("command -v xvfb-run").rc == 0) {
            launcher = "xvfb-run -a " + q;
            exr = render(launcher, r.view["spot_objects"], "eevee-soft",
                         eevee + " --eevee-soft-shadows on", why);
        }
        if (exr.empty()) {
            r.eeveeSkip =
                "EEVEE cannot render here (no OpenGL 3.3 through EGL or xvfb-run): " + why;
            return r;
        }
        r.exr["spot_objects/eevee-soft"] = exr;
        for (const std::string soft : {"on", "off"})
            r.exr["penumbra_square/eevee-" + std::string(soft == "on" ? "soft" : "hard")] = render(
                launcher, r.view["penumbra_square"], soft == "on" ? "eevee-soft" : "eevee-hard",
                eevee + " --eevee-soft-shadows " + soft, why);
        return r;
    }();
    return all;
}

#define SKIP_WITHOUT_BLENDER()                                               \
    do {                                                                     \
        const Renders& r_ = renders();                                       \
        if (!r_.skip.empty()) {                                              \
            ASSERT_EQ(r_.skip.find("(FAIL)"), std::string::npos) << r_.skip; \
            GTEST_SKIP() << r_.skip;                                         \
        }                                                                    \
    } while (0)

struct Errors {
    double mae = 0, penumbraMae = 0, noiseBound = 0;
    size_t pixels = 0, penumbraPixels = 0;
};

// Against the oracle over the pixels the camera sees (A = 1); the penumbra is 0 < V_oracle < 1.
// noiseBound: the mean over the penumbra of sqrt(2/pi) sqrt(V (1 - V) / spp + stderr^2).
Errors errors(const std::string& sceneName, const std::string& label, const std::string& light,
              int spp = 1) {
    const Renders& r = renders();
    const std::string& path = r.exr.at(sceneName + "/" + label);
    EXPECT_FALSE(path.empty()) << sceneName << "/" << label << " did not render";
    Errors e;
    if (path.empty()) return e;
    const ChannelImage oracle = readExr(r.oracle.at(sceneName).string());
    const ChannelImage image = readExr(path);
    EXPECT_EQ(image.width(), kWidth);
    EXPECT_EQ(image.height(), kHeight);
    EXPECT_TRUE(image.has(light + ".V")) << path;
    if (!image.has(light + ".V") || image.pixelCount() != oracle.pixelCount()) return e;
    const float* a = oracle.channel("A");
    const float* o = oracle.channel(light + ".V");
    const float* se = oracle.has(light + ".stderr") ? oracle.channel(light + ".stderr") : nullptr;
    const float* v = image.channel(light + ".V");
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        if (a[i] <= 0) continue;
        const double d = std::abs(double(o[i]) - double(v[i]));
        e.mae += d;
        ++e.pixels;
        if (o[i] > 0 && o[i] < 1) {
            e.penumbraMae += d;
            const double s = se ? double(se[i]) : 0.0;
            e.noiseBound +=
                std::sqrt(2.0 / M_PI) * std::sqrt(double(o[i]) * (1 - o[i]) / spp + s * s);
            ++e.penumbraPixels;
        }
    }
    if (e.pixels) e.mae /= double(e.pixels);
    if (e.penumbraPixels) {
        e.penumbraMae /= double(e.penumbraPixels);
        e.noiseBound /= double(e.penumbraPixels);
    }
    return e;
}

TEST(BlenderExternal, CyclesHardShadowsMatchTheOracle) {
    SKIP_WITHOUT_BLENDER();
    for (const std::string light : {"cone", "fill"}) {
        const Errors e = errors("spot_objects", "cycles", light);
        std::printf("spot_objects %s: Cycles %d spp mae %.5f over %zu px\n", light.c_str(),
                    kCyclesHardSpp, e.mae, e.pixels);
        EXPECT_GT(e.pixels, 1000u);
        EXPECT_LT(e.mae, 0.01) << light;
    }
}

TEST(BlenderExternal, CyclesAreaLightWithinItsSampleNoise) {
    SKIP_WITHOUT_BLENDER();
    const Errors e = errors("penumbra_square", "cycles", "panel", kCyclesAreaSpp);
    std::printf(
        "penumbra_square panel: Cycles %d spp mae %.5f, penumbra_mae %.5f over %zu px, "
        "independent-sample noise %.5f\n",
        kCyclesAreaSpp, e.mae, e.penumbraMae, e.penumbraPixels, e.noiseBound);
    EXPECT_GT(e.penumbraPixels, 200u);
    EXPECT_LT(e.penumbraMae, e.noiseBound);
    EXPECT_GT(e.penumbraMae, 0.0);  // a sampled estimate, not a copy of the oracle
    EXPECT_LT(e.mae, 0.01);
}

TEST(BlenderExternal, EeveeShowsItsArtifacts) {
    SKIP_WITHOUT_BLENDER();
    if (!renders().eeveeSkip.empty()) GTEST_SKIP() << renders().eeveeSkip;
    for (const std::string light : {"cone", "fill"}) {
        const Errors cycles = errors("spot_objects", "cycles", light);
        const Errors eevee = errors("spot_objects", "eevee-soft", light);
        std::printf("spot_objects %s: EEVEE soft, cube 512: mae %.5f (Cycles %.5f)\n",
                    light.c_str(), eevee.mae, cycles.mae);
        EXPECT_GT(eevee.mae, cycles.mae) << light;
        EXPECT_GT(eevee.mae, 1e-4) << light;
    }
    const Errors cycles = errors("penumbra_square", "cycles", "panel", kCyclesAreaSpp);
    const Errors soft = errors("penumbra_square", "eevee-soft", "panel");
    const Errors hard = errors("penumbra_square", "eevee-hard", "panel");
    std::printf("penumbra_square panel penumbra_mae: EEVEE soft %.5f, hard %.5f, Cycles %.5f\n",
                soft.penumbraMae, hard.penumbraMae, cycles.penumbraMae);
    EXPECT_GT(soft.penumbraMae, 2 * cycles.penumbraMae);
    EXPECT_GT(hard.penumbraMae, soft.penumbraMae);
}

// Reads metrics_wide.csv into rows of column -> value.
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& path) {
    std::ifstream in(path);
    std::string line;
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
    auto split = [](const std::string& s) {
        std::vector<std::string> cells;
        std::string cell;
        bool quoted = false;
        for (char c : s) {
            if (c == '"') {
                quoted = !quoted;
            } else if (c == ',' && !quoted) {
                cells.push_back(cell);
                cell.clear();
            } else {
                cell += c;
            }
        }
        cells.push_back(cell);
        return cells;
    };
    if (std::getline(in, line)) header = split(line);
    while (std::getline(in, line)) {
        const std::vector<std::string> cells = split(line);
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
        rows.push_back(row);
    }
    return rows;
}

double number(const std::map<std::string, std::string>& row, const std::string& key) {
    const auto it = row.find(key);
    return it == row.end() || it->second.empty() ? NAN : std::atof(it->second.c_str());
}

// The same renders graded by `compare --image` (docs/external.md): its rows must say
// what the direct reading says.
TEST(BlenderExternal, CompareGradesTheImages) {
    SKIP_WITHOUT_BLENDER();
    const Renders& r = renders();
    for (const std::string name : {"spot_objects", "penumbra_square"}) {
        std::string images;
        for (const auto& [key, path] : r.exr)
            if (key.rfind(name + "/", 0) == 0 && !path.empty())
                images += " --image " + key.substr(name.size() + 1) + "=" + quote(path);
        const fs::path out = workDir() / name / "report";
        fs::remove_all(out);
        const test::RunResult c =
            test::run("compare " + quote(scene(name).string()) + " --width " +
                      std::to_string(kWidth) + " --height " + std::to_string(kHeight) + images +
                      " --target-error 0.002 --threads 2 --no-cache --out " + quote(out.string()));
        ASSERT_EQ(c.exitCode, 0) << c.stderrText;
        const auto rows = readCsv(out / "metrics_wide.csv");
        std::map<std::string, std::map<std::string, std::string>> byKey;
        for (const auto& row : rows) byKey[row.at("label") + "/" + row.at("light")] = row;
        if (name == "spot_objects") {
            for (const std::string light : {"cone", "fill"}) {
                ASSERT_TRUE(byKey.count("cycles/" + light)) << light;
                EXPECT_LT(number(byKey["cycles/" + light], "mae"), 0.01) << light;
                if (byKey.count("eevee-soft/" + light)) {
                    EXPECT_GT(number(byKey["eevee-soft/" + light], "mae"),
                              number(byKey["cycles/" + light], "mae"))
                        << light;
                }
            }
        } else {
            ASSERT_TRUE(byKey.count("cycles/panel"));
            const Errors e = errors(name, "cycles", "panel", kCyclesAreaSpp);
            EXPECT_LT(number(byKey["cycles/panel"], "penumbra_mae"), e.noiseBound);
            if (byKey.count("eevee-soft/panel") && byKey.count("eevee-hard/panel")) {
                EXPECT_GT(number(byKey["eevee-hard/panel"], "penumbra_mae"),
                          number(byKey["eevee-soft/panel"], "penumbra_mae"));
            }
        }
    }
}

// Bad input: a non-zero exit and one line naming the problem.
TEST(BlenderExternal, BadViewIsOneLineAndNonZero) {
    std::string why;
    const std::string blender = findBlender(why);
    if (blender.empty()) GTEST_SKIP() << why;
    const fs::path dir = workDir() / "bad";
    fs::create_directories(dir);
    std::ofstream(dir / "view.json") << R"({"view_format": 2})";
    int rc = 0;
    EXPECT_TRUE(
        render(quote(blender), dir / "view.json", "out", "--engine cycles", why, &rc).empty());
    EXPECT_EQ(rc, 2);
    EXPECT_NE(why.find("view_format must be 1"), std::string::npos) << why;
    EXPECT_TRUE(
        render(quote(blender), dir / "view.json", "out", "--engine renderman", why, &rc).empty());
    EXPECT_EQ(rc, 2);
    EXPECT_NE(why.find("--engine must be cycles or eevee"), std::string::npos) << why;
}

}  // namespace
}  // namespace so
