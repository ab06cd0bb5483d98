// The commands that never touch an image never load OpenImageIO (docs/benchmarks.md): run the CLI
// under the dynamic linker's own log (LD_DEBUG=libs) and look for it.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

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

}  // namespace
