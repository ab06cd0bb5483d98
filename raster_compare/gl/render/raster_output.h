// The raster command's output folder (docs/cli.md): raster.exr, raster.json and a NAME.png preview
// per light, written from a typed RasterResult. The command, the C++ API (writeRenderOutput) and
// Python write the same files through here.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/scene.h"
#include "raster_compare/gl/render/raster_result.h"

namespace so {

// raster.json's format_version (docs/cli.md lists what each version added).
inline constexpr int kRasterJsonFormatVersion = 7;

struct RasterOutputFiles {
    std::filesystem::path exr, json;
    std::vector<std::string> previews;
};

// Writes the folder `dir` (created if missing; an InputError naming it when it cannot be) for
// `result`, `technique`'s render of `scene`; `scenePath` is raster.json's scene.file, as the
// caller gave it.
RasterOutputFiles writeRasterOutput(const std::filesystem::path& dir, const Scene& scene,
                                    const std::string& scenePath, const std::string& technique,
                                    const RasterResult& result, bool previews = true);

}  // namespace so
