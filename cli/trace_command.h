// `shadow-oracle trace`: load, run the oracle, write oracle.exr, oracle.json and NAME.png
// previews (docs/cli.md, docs/oracle.md).
#pragma once

#include <string>

#include "oracle/oracle.h"

namespace so {

struct TraceCommandOptions {
    std::string scenePath;
    std::string outDir;
    OracleOptions oracle;
};

// Returns the process exit code; InputError propagates to main (exit 2).
int runTraceCommand(const TraceCommandOptions& options);

// Shaded preview of one light: grey Lambert with a little ambient, times V, so a person sees the
// shadows (and the attached-shadow side) at a glance.
}  // namespace so
