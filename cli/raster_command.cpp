#include "cli/raster_command.h"

#include <iostream>

#include "cli/output.h"
#include "core/error.h"
#include "raster_compare/gl/gl_context.h"

namespace so {

std::unique_ptr<Technique> createTechniqueOfFlag(const std::string& flag, const std::string& name,
                                                 const std::vector<std::string>& settings) {
    asFlag(flag, [&] { findTechnique(name); });
    return createTechnique(name, settings);
}

int runRasterCommand(const RasterCommandOptions& options) {
    // Every setting is validated before the scene is read or a context made.
    const std::unique_ptr<Technique> technique =
        createTechniqueOfFlag("--technique", options.technique, options.settings);
    const Scene scene = loadScene(options.scenePath);
    printSceneWarnings(options.scenePath, scene);
    const std::filesystem::path out = makeOutputDir(options.outDir);

    GlContext gl;  // GlUnavailable propagates: main reports it
    RasterResult r;
    try {
        r = renderRaster(scene, *technique, options.raster, gl);
    } catch (const std::exception&) {
        printWarnings(gl.takeWarnings());  // the driver's warnings may explain a GlError
        throw;
    }
    printWarnings(gl.takeWarnings());
    writeExr((out / "raster.exr").string(), r.image,
             {{"shadowOracle/sceneHash", scene.contentHash},
              {"shadowOracle/toolVersion", toolVersionString()},
              {"shadowOracle/technique", technique->name()}});
    nlohmann::json j = {{"format_version", 6},
                        {"tool", toolJson()},
                        {"scene", {{"file", options.scenePath}, {"hash", scene.contentHash}}}};
    j.update(toJson(r.stats));
    writeJsonFile(out / "raster.json", j);
    std::cout << "rendered " << options.scenePath << " with " << technique->name() << " on "
              << gl.renderer() << "\n  " << (out / "raster.exr").string() << "\n  "
              << (out / "raster.json").string() << "\n";
    for (const std::string& png : writePreviews(out, r.image, scene.lights))
        std::cout << "  " << png << "\n";
    return 0;
}

}  // namespace so
