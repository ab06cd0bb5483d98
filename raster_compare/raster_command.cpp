#include "raster_compare/raster_command.h"

#include <filesystem>
#include <fstream>
#include <iostream>

#include "core/channels.h"
#include "core/error.h"
#include "core/version.h"
#include "raster_compare/gl_context.h"

namespace so {

int runRasterCommand(const RasterCommandOptions& options) {
    const ShadowTechnique& technique = findTechnique(options.technique);
    const ParamValues params = technique.parse(options.settings);
    technique.shaderDefines(params);  // validates what only the technique can (e.g. odd kernels)
    Scene scene = loadScene(options.scenePath);
    for (const std::string& w : scene.stats.warnings)
        std::cerr << "warning: " << options.scenePath << ": " << w << "\n";
    std::error_code ec;
    std::filesystem::create_directories(options.outDir, ec);
    if (ec) throwInputError(options.outDir, "--out", "cannot create the folder: " + ec.message());

    GlContext gl;  // GlUnavailable propagates: main reports it
    RasterResult r = renderRaster(scene, technique, params, options.raster, gl);
    const std::filesystem::path out(options.outDir);
    writeExr((out / "raster.exr").string(), r.image,
             {{"shadowOracle/sceneHash", scene.contentHash},
              {"shadowOracle/toolVersion", std::string(kToolVersion) + " " + kGitRevision},
              {"shadowOracle/technique", technique.name()}});
    nlohmann::json j = {
        {"format_version", 1},
        {"tool",
         {{"name", "shadow-oracle"}, {"version", kToolVersion}, {"git_revision", kGitRevision}}},
        {"scene", {{"file", options.scenePath}, {"hash", scene.contentHash}}}};
    j.update(r.stats);
    std::ofstream(out / "raster.json") << j.dump(2) << "\n";
    std::cout << "rendered " << options.scenePath << " with " << technique.name() << " on "
              << gl.renderer() << "\n  " << (out / "raster.exr").string() << "\n  "
              << (out / "raster.json").string() << "\n";
    // Previews: grey where lit, dark where shadowed.
    const float* A = r.image.channel(channels::kHit);
    for (const Light& light : scene.lights) {
        const float* V = r.image.channel(channels::lightChannel(light.name, channels::kVisibility));
        std::vector<float> rgb(r.image.pixelCount() * 3);
        for (size_t i = 0; i < r.image.pixelCount(); ++i) {
            const float g = A[i] == 0.0f ? 0.05f : 0.08f + 0.7f * V[i];
            rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = g;
        }
        const std::string png = (out / (light.name + ".png")).string();
        writePngRgb(png, r.image.width(), r.image.height(), rgb);
        std::cout << "  " << png << "\n";
    }
    return 0;
}

}  // namespace so
