// `shadow-oracle trace-merge`: joins the folders of `trace --tile I/N` into the whole image's
// oracle.exr (bit for bit what `trace` without --tile writes), oracle.json (the bands' stats
// merged) and the previews (docs/cli.md, docs/oracle.md "Tiles").
#pragma once

#include <string>
#include <vector>

namespace so {

struct TraceMergeOptions {
    std::vector<std::string> tileDirs;  // one output folder of trace --tile per band, any order
    std::string outDir;
    bool progress = true;
};

// Returns the process exit code; InputError (tiles that do not belong together, a band missing
// or given twice, a broken file) propagates to main (exit 2).
int runTraceMergeCommand(const TraceMergeOptions& options);

}  // namespace so
