#include "raster_compare/export/export_folder.h"

#include <system_error>

#include "core/camera.h"
#include "core/error.h"
#include "core/gltf_export.h"
#include "core/scene_writer.h"
#include "raster_compare/export/view_files.h"

namespace so {

ExportedFiles exportScene(const Scene& scene, const std::string& scenePath,
                          const OracleOptions& oracle, const std::filesystem::path& outDir) {
    std::error_code ec;
    std::filesystem::create_directories(outDir, ec);
    if (ec) throwInputError(outDir.string(), "", "cannot create the folder: " + ec.message());
    ExportedFiles files;
    files.glb = outDir / "scene.glb";
    files.sceneFile = outDir / "scene.scene.json";

    GlbExportOptions glb;
    glb.camera = effectiveCamera(scene, oracle);
    glb.sourcePath = scenePath;
    viewDepthRange(Camera(glb.camera), scene.wsBounds, glb.zNear, glb.zFar);
    const std::vector<unsigned char> bytes = sceneToGlb(scene, glb);
    writeFileBytes(files.glb, std::string(bytes.begin(), bytes.end()));
    writeFileBytes(files.sceneFile,
                   sceneFileJson(scene, glb.camera, files.glb.filename().string()).dump(2) + "\n");

    const ViewFiles view = writeViewFiles(scene, scenePath, oracle, outDir);
    files.viewJson = view.viewJson;
    files.gbufferExr = view.gbufferExr;
    return files;
}

}  // namespace so
