// `shadow-oracle export`: the scene as a folder for other engines (export/export_folder.h,
// docs/export.md): scene.glb, scene.scene.json, view.json, gbuffer.exr.
#pragma once

#include <string>

#include "oracle/oracle.h"

namespace so {

struct ExportCommandOptions {
    std::string scenePath;
    std::string outDir;
    OracleOptions oracle;  // width, height, threads
    // --frame K: the scene of a sequence posed at frame K (core/scene_pose.h); empty: as loaded.
    std::string frame;
    bool progress = true;  // --quiet: false
};

int runExportCommand(const ExportCommandOptions& options);

}  // namespace so
