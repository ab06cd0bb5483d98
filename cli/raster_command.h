// `shadow-oracle raster`: render a scene with one shadow-map technique, write raster.exr,
// raster.json and NAME.png previews (docs/cli.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "raster_compare/gl/renderer.h"
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

// The technique a command-line flag names, created (so its settings validated): an unknown name
// is an InputError naming the flag ("command line: --technique: unknown technique "nope" ...").
std::unique_ptr<Technique> createTechniqueOfFlag(const std::string& flag, const std::string& name,
                                                 const std::vector<std::string>& settings);

}  // namespace so
