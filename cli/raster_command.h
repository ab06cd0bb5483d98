// `shadow-oracle raster`: render a scene with one shadow-map technique, write raster.exr,
// raster.json and NAME.png previews (docs/cli.md).
#pragma once

#include <string>
#include <vector>

#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"

namespace so {

struct RasterCommandOptions {
    std::string scenePath;
    std::string outDir;
    std::string technique;
    std::vector<std::string> settings;  // key=value
    RasterOptions raster;
};

int runRasterCommand(const RasterCommandOptions& options);

}  // namespace so
