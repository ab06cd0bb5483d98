// A parameter's former name at the command line (issue 62, label gl): `raster` and `compare`
// accept planar's `alpha` (now `opacity`), render what `opacity` renders, and say the deprecation
// once on stderr.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "gl_test_context.h"

namespace so {
namespace {

using namespace so::test;
namespace fs = std::filesystem;

// The command's exit code; its stderr in `err`.
int runCli(const std::string& args, std::string* err) {
    const std::string log = "/tmp/so_former_" + std::to_string(::getpid()) + ".log";
    const int status =
        std::system((std::string(SO_CLI_PATH) + " " + args + " > /dev/null 2> " + log).c_str());
    std::ifstream in(log);
    err->assign(std::istreambuf_iterator<char>(in), {});
    fs::remove(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

const char* const kNotice =
    "warning: technique planar: `alpha` is deprecated, use `opacity`; accepted until format 8\n";

TEST(FormerNames, RasterAndCompareSayTheNoticeOnce) {
    REQUIRE_GL();
    const std::string scene = std::string(SO_SCENES_DIR) + "/contact_box.scene.json";
    const fs::path dir = fs::temp_directory_path() / ("so_former_" + std::to_string(::getpid()));
    const std::string size = " --width 32 --height 24 --frames 1 --warmup 0";
    std::string err;
    ASSERT_EQ(runCli("raster " + scene + " --out " + (dir / "old").string() +
                         " --technique planar --set alpha=0.5" + size,
                     &err),
              0)
        << err;
    EXPECT_EQ(count(err, kNotice), 1u) << err;
    ASSERT_EQ(runCli("raster " + scene + " --out " + (dir / "new").string() +
                         " --technique planar --set opacity=0.5" + size,
                     &err),
              0)
        << err;
    EXPECT_EQ(count(err, "deprecated"), 0u) << err;
    const auto parameters = [&](const char* run) {
        std::ifstream in(dir / run / "raster.json");
        return nlohmann::json::parse(in)["parameters"];
    };
    EXPECT_EQ(parameters("old"), parameters("new"));
    EXPECT_EQ(parameters("old")["opacity"], 0.5);
    EXPECT_EQ(readBytes(dir / "old" / "raster.exr"), readBytes(dir / "new" / "raster.exr"));
    ASSERT_EQ(runCli("compare " + scene + " --out " + (dir / "compare").string() +
                         " --technique planar:alpha=0.5 --technique planar" + size,
                     &err),
              0)
        << err;
    EXPECT_EQ(count(err, kNotice), 1u) << err;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so
