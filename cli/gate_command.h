// `shadow-oracle gate METRICS --limits LIMITS [--junit FILE]`: limits on metrics.json as an exit
// code for CI (docs/gate.md). 0: every limit holds; 1: at least one fails (one line each, with the
// measured value); 2: bad input.
#pragma once

#include <string>

namespace so {

struct GateOptions {
    std::string metricsPath;
    std::string limitsPath;
    std::string junitPath;  // empty: none
};

int runGateCommand(const GateOptions& options);

// Shell-style pattern: '*' any run, '?' any one character.
}  // namespace so
