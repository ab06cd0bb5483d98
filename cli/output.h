// What every command's output shares: the output folder, the provenance block of its JSON files,
// the scene's warnings on stderr; the JSON files and previews are core's (json_file.h, preview.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image.h"
#include "core/json_file.h"
#include "core/preview.h"
#include "core/scene.h"
#include "core/tool_info.h"
#include "raster_compare/pipeline/option_errors.h"  // asFlag, namingFlag

namespace so {

// The scene loader's warnings, one "warning: <file>: <text>" line each on stderr.
void printSceneWarnings(const std::string& scenePath, const Scene& scene);
// Warnings a library call collected (CachedOracle::warnings, GlContext::takeWarnings), one
// "warning: <text>" line each on stderr.
void printWarnings(const std::vector<std::string>& warnings);

// The absolute path of the running shadow-oracle (/proc/self/exe): what a sweep starts as child
// processes and names in its Slurm scripts.
std::filesystem::path thisExecutable();

}  // namespace so
