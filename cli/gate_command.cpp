#include "cli/gate_command.h"

#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/output.h"
#include "core/error.h"
#include "raster_compare/compare/gate.h"

namespace so {

using nlohmann::json;

namespace {

std::string xmlEscape(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
            case '&':
                o += "&amp;";
                break;
            case '<':
                o += "&lt;";
                break;
            case '>':
                o += "&gt;";
                break;
            case '"':
                o += "&quot;";
                break;
            default:
                o += c;
        }
    }
    return o;
}

std::string failureLine(const GateCheck& c) {
    std::ostringstream os;
    os << "FAIL " << c.scene << " " << c.light << " " << c.technique << " " << c.metric << " = "
       << *c.value << " > " << c.maximum;
    return os.str();
}

void writeJunit(const std::string& path, const std::vector<GateCheck>& checks, size_t failures) {
    std::ofstream x(path);
    if (!x) throwInputError(path, "--junit", "cannot be written");
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n  <testsuite "
         "name=\"shadow-oracle gate\" tests=\""
      << checks.size() << "\" failures=\"" << failures << "\">\n";
    for (const GateCheck& c : checks) {
        x << "    <testcase classname=\"" << xmlEscape(c.scene + "." + c.light) << "\" name=\""
          << xmlEscape(c.technique + " " + c.metric) << "\"";
        if (!c.value)
            x << ">\n      <skipped message=\"null: not applicable here\"/>\n    </testcase>\n";
        else if (!c.failed())
            x << "/>\n";
        else
            x << ">\n      <failure message=\"" << xmlEscape(failureLine(c))
              << "\"/>\n    </testcase>\n";
    }
    x << "  </testsuite>\n</testsuites>\n";
}

}  // namespace

int runGateCommand(const GateOptions& options) {
    const json metrics = readJsonFile(options.metricsPath, "metrics");
    const json limits = readJsonFile(options.limitsPath, "limits");
    const std::vector<GateCheck> checks =
        evaluateGate(metrics, options.metricsPath, limits, options.limitsPath);
    size_t failures = 0;
    for (const GateCheck& c : checks)
        if (c.failed()) {
            std::cout << failureLine(c) << "\n";
            ++failures;
        }
    size_t notApplicable = 0;
    for (const GateCheck& c : checks) notApplicable += !c.value;
    std::cout << checks.size() - failures << " passed";
    if (notApplicable)
        std::cout << " (" << notApplicable << " of them not applicable: the metric is null there)";
    std::cout << ", " << failures << " failed\n";
    if (!options.junitPath.empty()) writeJunit(options.junitPath, checks, failures);
    return failures ? 1 : 0;
}

}  // namespace so
