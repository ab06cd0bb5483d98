#include "cli/view_command.h"

#include "cli/progress_bar.h"
#include "cli/sequence_frames.h"

#include <iostream>

#include "cli/output.h"
#include "raster_compare/export/view_files.h"

namespace so {

int runViewCommand(const ViewCommandOptions& options) {
    const Scene loaded = loadScene(options.scenePath);
    printSceneWarnings(options.scenePath, loaded);
    const std::optional<Scene> posed = sceneAtFrameOption(loaded, options.scenePath, options.frame);
    const Scene& scene = posed ? *posed : loaded;
    const std::filesystem::path out = makeOutputDir(options.outDir, "--out");
    ProgressBar bar(options.progress);
    OracleOptions oracle = options.oracle;
    oracle.progress = bar.callback();
    const ViewFiles files = writeViewFiles(scene, options.scenePath, oracle, out);
    const CameraDesc desc = effectiveCamera(scene, options.oracle);
    std::cout << "view of " << options.scenePath << " (" << desc.width << " x " << desc.height
              << ")\n  " << files.viewJson.string() << "\n  " << files.gbufferExr.string() << "\n";
    return 0;
}

}  // namespace so
