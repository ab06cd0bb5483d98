#include "cli/raster_command.h"

#include <iostream>

#include "cli/output.h"
#include "core/error.h"
#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/raster_output.h"
#include "raster_compare/pipeline/option_errors.h"

namespace so {

int runRasterCommand(const RasterCommandOptions& options) {
    // Every setting is validated before the scene is read or a context made.
    const std::unique_ptr<Technique> technique =
        createTechniqueOfFlag("command line", "--technique", options.technique, options.settings);
    printWarnings(technique->values().deprecations());  // a former parameter name, said once
    const Scene scene = loadScene(options.scenePath);
    printSceneWarnings(options.scenePath, scene);
    const std::filesystem::path out = makeOutputDir(options.outDir, "--out");

    GlContext gl;  // GlUnavailable propagates: main reports it
    RasterResult r;
    try {
        r = renderConverged(scene, *technique, options.raster, gl);
    } catch (const std::exception&) {
        printWarnings(gl.takeWarnings());  // the driver's warnings may explain a GlError
        throw;
    }
    printWarnings(gl.takeWarnings());
    const RasterOutputFiles files =
        writeRasterOutput(out, scene, options.scenePath, technique->name(), r);
    std::cout << "rendered " << options.scenePath << " with " << technique->name() << " on "
              << gl.renderer() << "\n  " << files.exr.string() << "\n  " << files.json.string()
              << "\n";
    for (const std::string& png : files.previews) std::cout << "  " << png << "\n";
    return 0;
}

}  // namespace so
