// The commands that never touch an image never load OpenImageIO (docs/benchmarks.md): run the CLI
// under the dynamic linker's own log (LD_DEBUG=libs) and look for it.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

namespace {

std::string outputOf(const std::string& command) {
    std::unique_ptr<FILE, int (*)(FILE*)> p(::popen(command.c_str(), "r"), ::pclose);
    std::string out;
    if (!p) return out;
    char buf[4096];
    while (size_t n = std::fread(buf, 1, sizeof buf, p.get())) out.append(buf, n);
    return out;
}

TEST(ImageStartup, CommandsWithoutImagesDoNotLoadOpenImageIO) {
    for (const char* args : {"--version", "gate --help"}) {
        SCOPED_TRACE(args);
        const std::string log =
            outputOf(std::string("LD_DEBUG=libs '") + SO_CLI_PATH + "' " + args + " 2>&1");
        // The log works (it names what it initialises), and OpenImageIO is not in it.
        ASSERT_NE(log.find("calling init: "), std::string::npos) << log.substr(0, 2000);
        EXPECT_EQ(log.find("OpenImageIO"), std::string::npos);
    }
}

std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// trace writes its PNG previews with zlib alone (core/png_encode.h): it loads OpenImageIO only to
// read a texture (an alpha mask), and the previews change nothing else it writes.
TEST(ImageStartup, TraceLoadsOpenImageIOOnlyToReadATexture) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(testing::TempDir()) / "trace_previews";
    fs::remove_all(dir);
    const std::string tool = std::string("LD_DEBUG=libs '") + SO_CLI_PATH + "' trace '";
    const std::string small = "' --width 40 --height 30 --spp 16 --threads 2 --quiet --out '";
    const std::string square = tool + SO_SCENES_DIR + "/penumbra_square.scene.json" + small;
    const std::string with = outputOf(square + (dir / "with").string() + "' 2>&1");
    const std::string without =
        outputOf(square + (dir / "without").string() + "' --no-previews 2>&1");
    // The alpha grate reads its mask through OpenImageIO: the log sees it where it loads, so its
    // absence in the other two means something.
    const std::string grate = outputOf(tool + SO_SCENES_DIR + "/alpha_grate.scene.json" + small +
                                       (dir / "grate").string() + "' 2>&1");
    ASSERT_NE(grate.find("OpenImageIO"), std::string::npos) << grate.substr(0, 2000);
    for (const std::string* log : {&with, &without}) {
        ASSERT_NE(log->find("calling init: "), std::string::npos) << log->substr(0, 2000);
        EXPECT_EQ(log->find("OpenImageIO"), std::string::npos);
    }
    EXPECT_TRUE(fs::exists(dir / "with" / "panel.png"));
    EXPECT_FALSE(fs::exists(dir / "without" / "panel.png"));

    const std::string exr = fileBytes(dir / "with" / "oracle.exr");
    EXPECT_FALSE(exr.empty());
    EXPECT_EQ(exr, fileBytes(dir / "without" / "oracle.exr"));
    auto json = [&](const char* run) {
        return nlohmann::json::parse(fileBytes(dir / run / "oracle.json"));
    };
    const nlohmann::json a = json("with"), b = json("without"), g = json("grate");
    EXPECT_TRUE(a["libraries"]["png"].is_string());
    EXPECT_TRUE(b["libraries"]["png"].is_null());
    EXPECT_TRUE(a["libraries"]["openimageio"].is_null());
    EXPECT_TRUE(g["libraries"]["openimageio"].is_string());
    EXPECT_EQ(a["lights"][0]["rays_occluded"], b["lights"][0]["rays_occluded"]);
    EXPECT_EQ(a["lights"][0]["rays_traced"], b["lights"][0]["rays_traced"]);
    // The whole run's phases: the parts of the write add up to it, and the process outlasts them.
    const nlohmann::json& phases = a["phases_seconds"];
    EXPECT_NEAR(phases["write_exr"].get<double>() + phases["write_previews"].get<double>(),
                phases["write"].get<double>(), 1e-9);
    EXPECT_GE(phases["process"].get<double>() + 0.01, phases["primary"].get<double>() +
                                                          phases["shadow"].get<double>() +
                                                          phases["write"].get<double>());
}

}  // namespace
