// Which glTF extensions a file may use (docs/scene-format.md, "glTF extensions"): those the loader
// reads, those that only change shading (a shadow sees the same surface), and everything else,
// which is an error where the file requires it and ignored, with its name recorded, where the file
// only uses it. Internal to the glTF loader.
#pragma once

#include <string>
#include <vector>

#include "core/gltf_detail.h"

namespace so::gltf_detail {

struct GltfExtensions {
    bool meshQuantization = false;  // KHR_mesh_quantization in extensionsUsed
    // extensionsUsed that the loader does not read (shading-only ones included), sorted.
    std::vector<std::string> ignored;
};

// Checks extensionsUsed and extensionsRequired (arrays of strings; a required extension the
// loader cannot honour is an error naming it).
GltfExtensions checkExtensions(const Context& ctx, const Json& doc);

}  // namespace so::gltf_detail
