// Fuzzes the gate (raster_compare/compare/gate.cpp, evaluateGate, and baseline.cpp,
// compareToBaseline): its limits file, the metrics.json it checks and the baseline's metrics.json
// are all user input in CI. The input up to the first NUL byte is the limits file; what follows
// the NUL is metrics.json, up to a second NUL after which comes the baseline's metrics.json.
// Without a NUL, a small valid metrics.json is used for both, so mutations of the limits file
// reach the rule matching and the baseline's tolerances; without the second, the built-in one is
// the baseline, and each file is compared against the other both ways.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "raster_compare/compare/baseline.h"
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
    R"("missing_boundary":false}}}}],"oracle":{"stats":{"lights":[{"name":"key","worst_half_width":)"
    R"(0.01,"cost_curve":[{"penumbra_mean_half_width":0.02,"mean_half_width":0.01}]}]}}})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string_view input(reinterpret_cast<const char*>(data), size);
    const size_t nul = input.find('\0');
    const std::string_view rest =
        nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1);
    const size_t nul2 = rest.find('\0');
    auto limits = so::fuzz::parseJson(input.substr(0, nul));
    auto metrics =
        so::fuzz::parseJson(nul == std::string_view::npos ? kMetrics : rest.substr(0, nul2));
    auto baseline =
        so::fuzz::parseJson(nul2 == std::string_view::npos ? kMetrics : rest.substr(nul2 + 1));
    if (!limits || !metrics) return 0;
    so::fuzz::expectOnlyInputErrors([&] {
        for (const so::GateCheck& c :
             so::evaluateGate(*metrics, "metrics.json", *limits, "limits.json"))
            (void)c.failed();
    });
    if (!baseline) return 0;
    const auto compare = [&](const nlohmann::json& now, const nlohmann::json& old) {
        so::fuzz::expectOnlyInputErrors([&] {
            const so::BaselineComparison b = so::compareToBaseline(
                now, "metrics.json", old, "baseline.json", &*limits, "limits.json");
            for (const so::BaselineCheck& c : b.checks)
                if (c.applicable()) (void)(c.regressed() || c.improved());
            (void)b.failed();
        });
    };
    compare(*metrics, *baseline);
    compare(*baseline, *metrics);
    return 0;
}
