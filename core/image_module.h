// Finds and loads the OpenImageIO image module (core/image_oiio_module.cpp) on first use, so that
// only the processes that read an image pay for OpenImageIO's ~250 shared libraries
// (docs/benchmarks.md). Where it is looked for: docs/cli.md, "The image module".
#pragma once

#include <string>
#include <vector>

#include "core/image_module_abi.h"

namespace so {

// The module's function table, loaded on the first call (thread-safe; later calls are free).
// Throws InputError naming every path tried when no module loads; a later call tries again.
const SoImageModule& imageModule();

// The module's table if this process has loaded it (a texture was read), else null; loads nothing.
const SoImageModule* imageModuleIfLoaded();

// Where the module is looked for, in order: $SO_IMAGE_MODULE alone when set; else beside the
// running executable, in its ../core (the build tree's layout, for build/cli and build/tests),
// and the path the build wrote it to.
std::vector<std::string> imageModuleCandidates();

}  // namespace so
