#include "cli/export_command.h"

#include <iostream>

#include "cli/output.h"
#include "cli/progress_bar.h"
#include "cli/sequence_frames.h"
#include "raster_compare/export/export_folder.h"

namespace so {

int runExportCommand(const ExportCommandOptions& options) {
    const Scene loaded = loadScene(options.scenePath);
    printSceneWarnings(options.scenePath, loaded);
    const std::optional<Scene> posed = sceneAtFrameOption(loaded, options.scenePath, options.frame);
    const Scene& scene = posed ? *posed : loaded;
    const std::filesystem::path out = makeOutputDir(options.outDir, "--out");
    ProgressBar bar(options.progress);
    OracleOptions oracle = options.oracle;
    oracle.progress = bar.callback();
    const ExportedFiles files = exportScene(scene, options.scenePath, oracle, out);
    const CameraDesc desc = effectiveCamera(scene, options.oracle);
    std::cout << "export of " << options.scenePath << " (" << desc.width << " x " << desc.height
              << ")\n";
    for (const std::filesystem::path& p :
         {files.glb, files.sceneFile, files.viewJson, files.gbufferExr})
        std::cout << "  " << p.string() << "\n";
    return 0;
}

}  // namespace so
