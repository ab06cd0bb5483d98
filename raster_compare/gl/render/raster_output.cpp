#include "raster_compare/gl/render/raster_output.h"

#include "core/error.h"
#include "core/json_file.h"
#include "core/preview.h"
#include "core/tool_info.h"

namespace so {

namespace fs = std::filesystem;

RasterOutputFiles writeRasterOutput(const fs::path& dir, const Scene& scene,
                                    const std::string& scenePath, const std::string& technique,
                                    const RasterResult& result, bool previews) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throwInputError(dir.string(), "", "cannot create the folder: " + ec.message());
    RasterOutputFiles files{dir / "raster.exr", dir / "raster.json", {}};
    writeExr(files.exr.string(), result.image,
             {{"shadowOracle/sceneHash", scene.contentHash},
              {"shadowOracle/toolVersion", toolVersionString()},
              {"shadowOracle/technique", technique}});
    nlohmann::json j = {{"format_version", kRasterJsonFormatVersion},
                        {"tool", toolJson()},
                        {"scene", {{"file", scenePath}, {"hash", scene.contentHash}}}};
    j.update(toJson(result.stats));
    writeJsonFile(files.json, j);
    if (previews) files.previews = writePreviews(dir, result.image, scene.lights);
    return files;
}

}  // namespace so
