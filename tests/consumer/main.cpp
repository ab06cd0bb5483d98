// consumer SCENE ORACLE_EXR: traces SCENE through the installed library at ORACLE_EXR's size and
// checks that every channel equals the installed program's oracle.exr bit for bit; that a bad
// scene path is an exception with a one-line message, not an exit; and that two renders from two
// threads at once each equal a lone render (where no GL opens, it says so and skips that part).
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

#include <shadow_oracle/shadow_oracle.h>

namespace {

namespace so = shadow_oracle;

bool sameImage(const so::Image& a, const so::Image& b) {
    if (a.names != b.names || a.planes.size() != b.planes.size()) return false;
    for (size_t i = 0; i < a.planes.size(); ++i)
        if (a.planes[i].size() != b.planes[i].size() ||
            std::memcmp(a.planes[i].data(), b.planes[i].data(), a.planes[i].size() * 4) != 0)
            return false;
    return true;
}

// pcf and pcss rendered alone, then both at once from two threads, as a user's program would:
// 0 when each thread's image equals the lone one, 1 (with a message) otherwise.
int renderFromTwoThreads(const so::Scene& scene) {
    const char* techniques[2] = {"pcf", "pcss"};
    so::RenderOptions o;
    o.width = 64;
    o.height = 48;
    o.frames = 1;
    o.warmup = 0;
    so::RenderResult lone[2], together[2];
    try {
        for (int i = 0; i < 2; ++i) lone[i] = so::render(scene, techniques[i], {}, o);
    } catch (const so::Error& e) {
        const std::string why = e.what();
        if (why.find("EGL") == std::string::npos && why.find("OpenGL 4.5") == std::string::npos)
            throw;
        std::printf("consumer: no GL here, the two-thread render skipped (%s)\n", e.what());
        return 0;
    }
    std::string errors[2];
    std::thread threads[2];
    for (int i = 0; i < 2; ++i)
        threads[i] = std::thread([&, i] {
            try {
                together[i] = so::render(scene, techniques[i], {}, o);
            } catch (const std::exception& e) {
                errors[i] = e.what();
            }
        });
    for (std::thread& t : threads) t.join();
    for (int i = 0; i < 2; ++i) {
        if (!errors[i].empty()) {
            std::fprintf(stderr, "render %s from a second thread: %s\n", techniques[i],
                         errors[i].c_str());
            return 1;
        }
        if (!sameImage(lone[i].image, together[i].image)) {
            std::fprintf(stderr, "render %s from two threads differs from a lone render\n",
                         techniques[i]);
            return 1;
        }
    }
    std::printf(
        "consumer: pcf and pcss rendered from two threads at once, each equal to a lone "
        "render\n");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: consumer SCENE ORACLE_EXR\n");
        return 2;
    }
    const so::Image cli = so::readExr(argv[2]);
    so::TraceOptions options;
    options.width = cli.width;
    options.height = cli.height;
    const so::Scene scene = so::Scene::load(argv[1]);
    const so::TraceResult oracle = so::trace(scene, options);
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
    if (renderFromTwoThreads(scene) != 0) return 1;
    std::printf(
        "consumer: %s traced through ShadowOracle %s: %zu channels equal to the program's, "
        "%.3f s\n",
        argv[1], so::version().c_str(), cli.names.size(), oracle.seconds);
    return 0;
}
