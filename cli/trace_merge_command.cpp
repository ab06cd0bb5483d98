#include "cli/trace_merge_command.h"

#include <iostream>

#include "cli/output.h"
#include "cli/progress_bar.h"
#include "oracle/trace_merge.h"

namespace so {

int runTraceMergeCommand(const TraceMergeOptions& options) {
    TraceMergeFiles files;
    {
        ProgressBar bar(options.progress);
        files = mergeTraceTiles(
            options.tileDirs, [&] { return makeOutputDir(options.outDir, "--out"); },
            bar.callback());
    }
    std::cout << "merged " << files.tiles << " tiles (" << files.width << "x" << files.height
              << ")\n  " << files.exr.string() << "\n  " << files.json.string() << "\n";
    for (const std::string& p : files.previews) std::cout << "  " << p << "\n";
    return 0;
}

}  // namespace so
