// The join of `trace --tile I/N`'s folders: the whole image's oracle.exr (bit for bit what `trace`
// without --tile writes), oracle.json (the bands' stats merged) and the previews (docs/cli.md,
// docs/oracle.md "Tiles"). In the oracle's library, beside writeTraceOutput, so the merge links no
// GL. What `shadow-oracle trace-merge` runs.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/progress.h"

namespace so {

struct TraceMergeFiles {
    size_t tiles = 0;
    int width = 0, height = 0;  // the whole image's
    std::filesystem::path exr, json;
    std::vector<std::string> previews;
};

// Reads the bands (one output folder of trace --tile each, any order) and writes the whole image's
// files into the folder `makeOut` returns, called once the bands are read and joined (so a bad
// band leaves no folder; the caller names its own option when the folder cannot be made).
// InputError (tiles that do not belong together, a band missing or given twice, a broken file)
// before anything is written; `progress` sees the EXR's writing ("writing <path>").
TraceMergeFiles mergeTraceTiles(const std::vector<std::string>& tileDirs,
                                const std::function<std::filesystem::path()>& makeOut,
                                const ProgressCallback& progress = {});

}  // namespace so
