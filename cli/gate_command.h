// `shadow-oracle gate METRICS [--limits LIMITS] [--baseline OLD] [--junit FILE] [--summary MD]`:
// limits on metrics.json, and its metrics against an earlier run's, as an exit code for CI
// (docs/gate.md). 0: every limit holds and nothing regressed; 1: a limit fails, a metric regressed
// or a row of the baseline is missing (one line each); 2: bad input.
#pragma once

#include <string>

namespace so {

struct GateOptions {
    std::string metricsPath;
    std::string limitsPath;    // empty: none (then baselinePath is given)
    std::string baselinePath;  // empty: none; else the last good run's metrics.json
    std::string junitPath;     // empty: none
    std::string summaryPath;   // empty: none; else a Markdown summary for a pull request
};

int runGateCommand(const GateOptions& options);
}  // namespace so
