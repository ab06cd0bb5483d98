// `shadow-oracle view`: view.json and gbuffer.exr (export/view_files.h, docs/external.md).
#pragma once

#include <string>

#include "core/scene.h"
#include "oracle/oracle.h"

namespace so {

struct ViewCommandOptions {
    std::string scenePath;
    std::string outDir;
    OracleOptions oracle;  // width, height, threads
    // --frame K: the scene of a sequence posed at frame K (core/scene_pose.h); empty: as loaded.
    std::string frame;
    bool progress = true;  // --quiet: false
};

int runViewCommand(const ViewCommandOptions& options);

}  // namespace so
