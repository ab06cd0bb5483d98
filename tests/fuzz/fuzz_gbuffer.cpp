// Fuzzes the G-buffer reader of `trace --points` (core/gbuffer.cpp, readGBuffer). The input is
// the EXR file, written to the scratch folder and read with the fuzz limits (at most 2^20 pixels,
// 1024 per side), so that no input can make the reader allocate more than about 50 MB of planes.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/gbuffer.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = so::fuzz::scratchDir() / "gbuffer.exr";
    so::fuzz::writeFile(path, std::string_view(reinterpret_cast<const char*>(data), size));
    so::fuzz::expectOnlyInputErrors([&] {
        const so::GBuffer g = so::readGBuffer(path.string(), so::fuzz::fuzzLimits());
        // What the oracle relies on: every plane has one value per pixel, all four replay
        // channels or none.
        const size_t n = g.pixelCount();
        if (g.coverage.size() != n || g.wsPX.size() != n || g.wsNZ.size() != n ||
            (g.hasReplay() && (g.primId.size() != n || g.baryV.size() != n)) ||
            (!g.depth.empty() && g.depth.size() != n))
            std::abort();
    });
    return 0;
}
