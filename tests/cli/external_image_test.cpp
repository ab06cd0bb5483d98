// compare --image (issue 29, docs/external.md "Images in"): a renderer's image judged exactly as a
// built-in technique is. Against closed answers: the oracle's own visibility scores 0 (EXR bit for
// bit; PNG within its quantisation), a shifted image scores what computeLightMetrics gives on the
// same pair; every bad input is one line and exit 2 with nothing written; the row reaches the
// CSVs, the report, the index page and the gate; without a cost file its costs are null.
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "core/channels.h"
#include "core/image.h"
#include "raster_compare/compare/metrics.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using so::test::run;
namespace ch = so::channels;

const std::string kSpot = SO_SCENES_DIR "/spot_objects.scene.json";     // cone (spot), fill (point)
const std::string kRect = SO_SCENES_DIR "/penumbra_square.scene.json";  // panel (rect, sampled)
constexpr int kW = 64, kH = 48;
const std::string kSize = " --width 64 --height 48";

fs::path scratch(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("so_external_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

so::ChannelImage traceOracle(const std::string& scene, const fs::path& dir) {
    const auto r = run("trace " + scene + " --out " + dir.string() + kSize + " --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    return so::readExr((dir / "oracle.exr").string());
}

// The named channels of `from` under their own names, shifted `dx` pixels to the right.
void writeVisibility(const fs::path& path, const so::ChannelImage& from,
                     const std::vector<std::string>& names, int dx = 0) {
    so::ChannelImage img(from.width(), from.height());
    for (const std::string& n : names) {
        float* dst = img.addChannel(n);
        const float* src = from.channel(n);
        for (int y = 0; y < from.height(); ++y)
            for (int x = 0; x < from.width(); ++x)
                dst[size_t(y) * size_t(from.width()) + size_t(x)] =
                    src[size_t(y) * size_t(from.width()) +
                        size_t(std::clamp(x - dx, 0, from.width() - 1))];
    }
    so::writeExr(path.string(), img);
}

// A 16-bit grey PNG, written here (the project writes only 8-bit PNGs): signature, IHDR, one
// zlib-compressed IDAT of filter-0 rows, IEND.
void writePng16(const fs::path& path, int w, int h, const std::vector<uint16_t>& grey) {
    auto be32 = [](std::string& s, uint32_t v) {
        for (int k = 3; k >= 0; --k) s += char((v >> (8 * k)) & 0xFF);
    };
    auto chunk = [&](std::string& out, const char* type, const std::string& data) {
        be32(out, uint32_t(data.size()));
        const std::string body = std::string(type, 4) + data;
        out += body;
        be32(out,
             uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    };
    std::string ihdr;
    be32(ihdr, uint32_t(w));
    be32(ihdr, uint32_t(h));
    ihdr +=
        std::string("\x10\x00\x00\x00\x00", 5);  // 16 bit, grey, deflate, filter 0, no interlace
    std::string raw;
    for (int y = 0; y < h; ++y) {
        raw += '\0';
        for (int x = 0; x < w; ++x) {
            const uint16_t v = grey[size_t(y) * size_t(w) + size_t(x)];
            raw += char(v >> 8);
            raw += char(v & 0xFF);
        }
    }
    uLongf size = compressBound(uLong(raw.size()));
    std::string z(size, '\0');
    compress(reinterpret_cast<Bytef*>(z.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
             uLong(raw.size()));
    z.resize(size);
    std::string png("\x89PNG\r\n\x1a\n", 8);
    chunk(png, "IHDR", ihdr);
    chunk(png, "IDAT", z);
    chunk(png, "IEND", "");
    std::ofstream(path, std::ios::binary) << png;
}

json readJson(const fs::path& p) {
    std::ifstream in(p);
    return json::parse(in);
}

const json& rowOf(const json& metrics, const std::string& label) {
    for (const json& r : metrics["results"])
        if (r["label"] == label) return r;
    ADD_FAILURE() << "no row " << label;
    return metrics["results"][0];
}

TEST(ExternalImage, TheOraclesOwnVisibilityScoresZero) {
    const fs::path d = scratch("zero");
    const so::ChannelImage spot = traceOracle(kSpot, d / "spot");
    writeVisibility(d / "spot.exr", spot, {"cone.V", "fill.V"});
    auto r = run("compare " + kSpot + kSize + " --image oracle=" + (d / "spot.exr").string() +
                 " --out " + (d / "cmp_spot").string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    json m = readJson(d / "cmp_spot" / "metrics.json");
    EXPECT_EQ(m["schema_version"], so::kMetricsSchemaVersion);
    EXPECT_TRUE(m["gl"].is_null());  // images alone need no GL
    const json& row = rowOf(m, "oracle");
    EXPECT_EQ(row["source"], "external");
    for (const char* light : {"cone", "fill"}) {
        EXPECT_EQ(row["lights"][light]["mae"], 0.0) << light;
        EXPECT_EQ(row["lights"][light]["max_abs"], 0.0) << light;
        // No cost file: every cost unknown, not zero.
        for (const char* c : {"frame_ms", "shadow_map_ms", "visibility_ms", "memory_bytes"})
            EXPECT_TRUE(row["lights"][light]["cost"][c].is_null()) << c;
    }
    EXPECT_NE(so::test::readBytes(d / "cmp_spot" / "report.html")
                  .find("Times were measured on <b>none: the images have no cost files</b>"),
              std::string::npos);

    // A sampled area light through a 16-bit PNG: within half a code of the oracle's V.
    const so::ChannelImage rect = traceOracle(kRect, d / "rect");
    std::vector<uint16_t> codes(rect.pixelCount());
    for (size_t i = 0; i < codes.size(); ++i)
        codes[i] = uint16_t(std::lround(rect.channel("panel.V")[i] * 65535.0f));
    writePng16(d / "rect.png", kW, kH, codes);
    r = run("compare " + kRect + kSize + " --image png16=" + (d / "rect.png").string() + " --out " +
            (d / "cmp_rect").string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    m = readJson(d / "cmp_rect" / "metrics.json");
    const double maxAbs = rowOf(m, "png16")["lights"]["panel"]["max_abs"];
    EXPECT_LE(maxAbs, 0.5 / 65535.0 + 1e-7);
    fs::remove_all(d);
}

TEST(ExternalImage, AShiftedImageScoresWhatTheMetricsGiveOnTheSamePair) {
    const fs::path d = scratch("shift");
    const so::ChannelImage oracle = traceOracle(kSpot, d / "trace");
    writeVisibility(d / "shift.exr", oracle, {"cone.V", "fill.V"}, 3);
    std::ofstream(d / "shift.exr.json")
        << R"({"renderer": "test engine", "frame_ms": 2.5, "memory_bytes": 1024,
              "params": {"bias": 0.25, "mode": "pcf"}})";
    const auto r =
        run("compare " + kSpot + kSize + " --image shifted=" + (d / "shift.exr").string() +
            " --out " + (d / "cmp").string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const json m = readJson(d / "cmp" / "metrics.json");
    const json& row = rowOf(m, "shifted");
    EXPECT_EQ(row["renderer"], "test engine");
    EXPECT_EQ(row["parameters"]["mode"], "pcf");
    // What the metrics give on the oracle (as compare traced it) and the same shifted image.
    const so::ChannelImage cmpOracle = so::readExr((d / "cmp" / "oracle.exr").string());
    const so::ChannelImage raster = so::readExr((d / "cmp" / "shifted" / "raster.exr").string());
    so::MetricOptions mo;
    mo.contactThreshold = 0.01 * double(m["scene"]["extent"]);
    for (const char* light : {"cone", "fill"}) {
        const so::LightMetrics direct = so::computeLightMetrics(cmpOracle, raster, light, mo);
        const json& got = row["lights"][light];
        EXPECT_GT(direct.mae, 0.0) << light;
        EXPECT_EQ(got["mae"], direct.mae) << light;
        EXPECT_EQ(got["false_lit_rate"], direct.falseLitRate) << light;
        EXPECT_EQ(got["false_shadow_rate"], direct.falseShadowRate) << light;
        EXPECT_EQ(got["cost"]["frame_ms"], 2.5);
        EXPECT_TRUE(got["cost"]["frame_ms_p25"].is_null());
        EXPECT_TRUE(got["cost"]["visibility_ms"].is_null());
        EXPECT_EQ(got["cost"]["memory_bytes"], 1024);
    }
    // The V the row was judged on is the file's, shifted.
    EXPECT_EQ(raster.channel("cone.V")[10 * kW + 20], oracle.channel("cone.V")[10 * kW + 17]);
    fs::remove_all(d);
}

TEST(ExternalImage, BadInputIsOneLineExitTwoAndWritesNothing) {
    const fs::path d = scratch("bad");
    const so::ChannelImage oracle = traceOracle(kSpot, d / "trace");
    writeVisibility(d / "good.exr", oracle, {"cone.V", "fill.V"});
    writeVisibility(d / "nofill.exr", oracle, {"cone.V"});
    {
        so::ChannelImage small(kW / 2, kH / 2);
        small.addChannel("cone.V");
        small.addChannel("fill.V");
        so::writeExr((d / "small.exr").string(), small);
        for (const auto& [name, value] : {std::pair{"nan.exr", NAN}, std::pair{"big.exr", 1.5f}}) {
            so::ChannelImage img(kW, kH);
            img.addChannel("cone.V", 0.5f)[7] = value;
            img.addChannel("fill.V", 0.5f);
            so::writeExr((d / name).string(), img);
        }
    }
    fs::create_directories(d / "badcost");
    writeVisibility(d / "badcost" / "img.exr", oracle, {"cone.V", "fill.V"});
    std::ofstream(d / "badcost" / "img.exr.json") << R"({"frame_ms": 1, "fps": 60})";
    const std::string good = (d / "good.exr").string();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--image x=" + (d / "small.exr").string(), "size"},
        {"--image x=" + (d / "nofill.exr").string(), "fill.V"},
        {"--image x=" + (d / "nan.exr").string(), "cone.V"},
        {"--image x=" + (d / "big.exr").string(), "cone.V"},
        {"--image x=" + (d / "badcost" / "img.exr").string(), "fps"},
        {"--image x=" + good + " --image-encoding gamma", "--image-encoding"},
        {"--image " + good, "--image"},
        {"--image x=" + good + " --image x=" + good, "--image"},
        {"--image x=" + (d / "missing.exr").string(), "missing.exr"},
        {"--image x=" + good + " --frames-path 3", "--frames-path"},
        {"", "--technique"}};
    for (const auto& [args, field] : cases) {
        const fs::path out = d / "out";
        const auto r = run("compare " + kSpot + kSize + " " + args + " --out " + out.string());
        EXPECT_EQ(r.exitCode, 2) << args << ": " << r.stderrText;
        EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
        EXPECT_NE(r.stderrText.find(field), std::string::npos) << args << ": " << r.stderrText;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
    fs::remove_all(d);
}

// With a built-in technique beside it (GL): the image's row in both CSVs, the report, the index
// page and the gate, as any technique's.
TEST(ExternalImage, TheRowReachesEveryOutput) {
    const fs::path d = scratch("rows");
    const so::ChannelImage oracle = traceOracle(kSpot, d / "trace");
    writeVisibility(d / "mine.exr", oracle, {"cone.V", "fill.V"}, 2);
    const fs::path cmp = d / "cmp";
    auto r = run("compare " + kSpot + kSize + " --frames 1 --technique basic --image mine=" +
                 (d / "mine.exr").string() + " --out " + cmp.string());
    if (r.exitCode == 1 && r.stderrText.find("no OpenGL") != std::string::npos)
        GTEST_SKIP() << r.stderrText;
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const std::string csv = so::test::readBytes(cmp / "metrics.csv");
    EXPECT_NE(csv.find(",cone,external,mine,mae,"), std::string::npos);
    EXPECT_NE(csv.find(",cone,external,mine,cost.frame_ms,\n"), std::string::npos);  // empty
    const std::string wide = so::test::readBytes(cmp / "metrics_wide.csv");
    EXPECT_NE(wide.find(",external,mine,"), std::string::npos);
    const std::string html = so::test::readBytes(cmp / "report.html");
    EXPECT_NE(html.find(">mine<"), std::string::npos);
    EXPECT_NE(html.find("external"), std::string::npos);
    EXPECT_TRUE(fs::exists(cmp / "error_mine.exr"));
    // No cost file: the times are the GL renderer's alone, and the image's cells are empty.
    EXPECT_EQ(html.find("the images by"), std::string::npos);
    r = run("index " + cmp.string() + " --out " + (d / "index.html").string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_NE(so::test::readBytes(d / "index.html").find("mine"), std::string::npos);
    // The gate: a limit on the image's label fails, naming it; a loose one passes.
    std::ofstream(d / "strict.json") << R"({"limits_format": 1, "default": {},
        "rules": [{"technique": "mine", "max": {"mae": 0.0}}]})";
    std::ofstream(d / "loose.json") << R"({"limits_format": 1, "default": {},
        "rules": [{"technique": "mine", "max": {"mae": 1.0, "cost.frame_ms": 0.0}}]})";
    r = run("gate " + (cmp / "metrics.json").string() + " --limits " +
            (d / "strict.json").string());
    EXPECT_EQ(r.exitCode, 1) << r.stdoutText;
    EXPECT_NE(r.stdoutText.find("FAIL spot_objects.scene.json cone mine mae"), std::string::npos)
        << r.stdoutText;
    r = run("gate " + (cmp / "metrics.json").string() + " --limits " + (d / "loose.json").string());
    EXPECT_EQ(r.exitCode, 0) << r.stdoutText;  // a null cost is not applicable, not 0
    EXPECT_NE(r.stdoutText.find("not applicable"), std::string::npos) << r.stdoutText;
    fs::remove_all(d);
}

// compare --points: the oracle at view's G-buffer, the image its own V: 0 error.
TEST(ExternalImage, PointsJudgeTheImageOnTheGbuffersPixels) {
    const fs::path d = scratch("points");
    auto r = run("view " + kSpot + kSize + " --out " + (d / "view").string() + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const so::ChannelImage oracle = traceOracle(kSpot, d / "trace");
    writeVisibility(d / "mine.exr", oracle, {"cone.V", "fill.V"});
    r = run("compare " + kSpot + " --points " + (d / "view" / "gbuffer.exr").string() +
            " --image mine=" + (d / "mine.exr").string() + " --out " + (d / "cmp").string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const json m = readJson(d / "cmp" / "metrics.json");
    for (const char* light : {"cone", "fill"})
        EXPECT_EQ(rowOf(m, "mine")["lights"][light]["mae"], 0.0) << light;
    r = run("compare " + kSpot + " --points " + (d / "view" / "gbuffer.exr").string() +
            " --technique basic --out " + (d / "cmp2").string());
    EXPECT_EQ(r.exitCode, 2) << r.stderrText;
    EXPECT_NE(r.stderrText.find("--points"), std::string::npos) << r.stderrText;
    fs::remove_all(d);
}

}  // namespace
