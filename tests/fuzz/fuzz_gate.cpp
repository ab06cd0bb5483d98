// Fuzzes the gate (raster_compare/compare/gate.cpp, evaluateGate): its limits file and the
// metrics.json it checks are both user input in CI. The input up to the first NUL byte is the
// limits file; what follows the NUL is metrics.json. Without a NUL, a small valid metrics.json is
// used, so mutations of the limits file reach the rule matching.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "raster_compare/compare/gate.h"
#include "tests/fuzz/fuzz_common.h"
#include "tests/fuzz/fuzz_json_input.h"

namespace {

constexpr std::string_view kMetrics =
    R"({"schema_version":4,"scene":{"file":"scenes/contact_box.scene.json"},"results":[)"
    R"({"label":"basic","technique":"basic","family":"shadow map","lights":{"key":{)"
    R"("acne_rate":0.31,"false_lit_rate":0.001,"peter_panning_rate":0.0,"mae":0.26,)"
    R"("penumbra_mae":null,"boundary_displacement_px":{"max":157.9,"mean":59.2,"p95":126.9,)"
    R"("missing_boundary":false}}}},)"
    R"({"label":"pcf_kernel_5","technique":"pcf","family":"shadow map","lights":{"key":{)"
    R"("acne_rate":0.01,"false_lit_rate":0.02,"peter_panning_rate":0.04,"mae":0.05,)"
    R"("penumbra_mae":0.2,"boundary_displacement_px":{"max":3.0,"mean":1.0,"p95":2.5,)"
    R"("missing_boundary":false}}}}]})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string_view input(reinterpret_cast<const char*>(data), size);
    size_t nul = input.find('\0');
    auto limits = so::fuzz::parseJson(input.substr(0, nul));
    auto metrics =
        so::fuzz::parseJson(nul == std::string_view::npos ? kMetrics : input.substr(nul + 1));
    if (!limits || !metrics) return 0;
    so::fuzz::expectOnlyInputErrors([&] {
        for (const so::GateCheck& c :
             so::evaluateGate(*metrics, "metrics.json", *limits, "limits.json"))
            (void)c.failed();
    });
    return 0;
}
