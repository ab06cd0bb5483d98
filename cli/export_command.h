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
    bool progress = true;  // --quiet: false
};

int runExportCommand(const ExportCommandOptions& options);

}  // namespace so
