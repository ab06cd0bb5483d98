// Fuzzes the `index` command's reader of metrics.json (raster_compare/compare/index_page.cpp,
// parseSceneMetrics). The input is the metrics.json file.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "raster_compare/compare/index_page.h"
#include "tests/fuzz/fuzz_common.h"
#include "tests/fuzz/fuzz_json_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    auto metrics = so::fuzz::parseJson(std::string_view(reinterpret_cast<const char*>(data), size));
    if (!metrics) return 0;
    so::fuzz::expectOnlyInputErrors([&] { (void)so::parseSceneMetrics(*metrics, "metrics.json"); });
    return 0;
}
