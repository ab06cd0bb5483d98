// The replay driver of the normal build (no libFuzzer): runs LLVMFuzzerTestOneInput on every file
// named on the command line and every file under every folder named, in sorted order, so that each
// input in tests/fuzz/corpus/ and tests/fuzz/regressions/ is tested by every build
// (docs/fuzzing.md).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    std::vector<fs::path> files;
    for (int i = 1; i < argc; ++i) {
        fs::path arg(argv[i]);
        std::error_code ec;
        if (fs::is_directory(arg, ec)) {
            for (const auto& e : fs::recursive_directory_iterator(arg))
                if (e.is_regular_file() && e.path().filename().string()[0] != '.')
                    files.push_back(e.path());
        } else if (fs::is_regular_file(arg, ec)) {
            files.push_back(arg);
        } else if (fs::exists(arg, ec)) {
            std::fprintf(stderr, "replay: %s: not a file or folder\n", argv[i]);
            return 2;
        } else {
            // tests/fuzz/regressions/<harness>/ exists only once that harness has had a finding.
            std::fprintf(stderr, "replay: %s: absent, nothing to replay there\n", argv[i]);
        }
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        std::ifstream in(f, std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
        if (!in.eof() && in.fail()) {
            std::fprintf(stderr, "replay: %s: cannot be read\n", f.c_str());
            return 2;
        }
        std::fprintf(stderr, "replay: %s (%zu bytes)\n", f.c_str(), bytes.size());
        LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    }
    if (files.empty()) {
        std::fprintf(stderr, "replay: no input found\n");
        return 2;
    }
    std::printf("replay: %zu inputs, no finding\n", files.size());
    return 0;
}
