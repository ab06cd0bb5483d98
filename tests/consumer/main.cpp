// consumer SCENE ORACLE_EXR: traces SCENE through the installed library at ORACLE_EXR's size and
// checks that every channel equals the installed program's oracle.exr bit for bit; then that a
// bad scene path is an exception with a one-line message, not an exit.
#include <cstdio>
#include <cstring>

#include <shadow_oracle/shadow_oracle.h>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: consumer SCENE ORACLE_EXR\n");
        return 2;
    }
    namespace so = shadow_oracle;
    const so::Image cli = so::readExr(argv[2]);
    so::TraceOptions options;
    options.width = cli.width;
    options.height = cli.height;
    const so::TraceResult oracle = so::trace(so::Scene::load(argv[1]), options);
    if (oracle.image.names.size() != cli.names.size()) {
        std::fprintf(stderr, "%zu channels, the program wrote %zu\n", oracle.image.names.size(),
                     cli.names.size());
        return 1;
    }
    for (size_t i = 0; i < cli.names.size(); ++i) {
        const std::vector<float>& mine = oracle.image.channel(cli.names[i]);
        if (std::memcmp(mine.data(), cli.planes[i].data(), mine.size() * sizeof(float)) != 0) {
            std::fprintf(stderr, "channel %s differs from the program's\n", cli.names[i].c_str());
            return 1;
        }
    }
    try {
        so::Scene::load("no/such/scene.json");
        std::fprintf(stderr, "a missing scene loaded\n");
        return 1;
    } catch (const so::Error& e) {
        if (std::strchr(e.what(), '\n') || !std::strstr(e.what(), "no such file")) {
            std::fprintf(stderr, "unexpected message: %s\n", e.what());
            return 1;
        }
    }
    std::printf(
        "consumer: %s traced through ShadowOracle %s: %zu channels equal to the program's, "
        "%.3f s\n",
        argv[1], so::version().c_str(), cli.names.size(), oracle.seconds);
    return 0;
}
