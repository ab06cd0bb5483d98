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

// trace encodes no image but its previews: with --no-previews it must not load OpenImageIO, and
// everything else it writes is what it writes with them.
TEST(ImageStartup, TraceWithoutPreviewsDoesNotLoadOpenImageIO) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(testing::TempDir()) / "trace_no_previews";
    fs::remove_all(dir);
    const std::string trace = std::string("LD_DEBUG=libs '") + SO_CLI_PATH + "' trace '" +
                              SO_SCENES_DIR + "/penumbra_square.scene.json' --width 40 " +
                              "--height 30 --spp 16 --threads 2 --quiet --out '";
    const std::string with = outputOf(trace + (dir / "with").string() + "' 2>&1");
    const std::string without =
        outputOf(trace + (dir / "without").string() + "' --no-previews 2>&1");
    // The log sees OpenImageIO where the previews need it, so its absence below means something.
    ASSERT_NE(with.find("OpenImageIO"), std::string::npos) << with.substr(0, 2000);
    EXPECT_TRUE(fs::exists(dir / "with" / "panel.png"));
    ASSERT_NE(without.find("calling init: "), std::string::npos) << without.substr(0, 2000);
    EXPECT_EQ(without.find("OpenImageIO"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "without" / "panel.png"));

    const std::string exr = fileBytes(dir / "with" / "oracle.exr");
    EXPECT_FALSE(exr.empty());
    EXPECT_EQ(exr, fileBytes(dir / "without" / "oracle.exr"));
    auto json = [&](const char* run) {
        return nlohmann::json::parse(fileBytes(dir / run / "oracle.json"));
    };
    const nlohmann::json a = json("with"), b = json("without");
    EXPECT_TRUE(a["libraries"]["openimageio"].is_string());
    EXPECT_TRUE(b["libraries"]["openimageio"].is_null());
    EXPECT_EQ(a["lights"][0]["rays_occluded"], b["lights"][0]["rays_occluded"]);
    EXPECT_EQ(a["lights"][0]["rays_traced"], b["lights"][0]["rays_traced"]);
}

}  // namespace
