// The GLB container (glTF 2.0 spec, "GLB File Format Specification"): its header and chunks,
// checked more strictly than tinygltf does, and the file rebuilt around a rewritten JSON chunk.
// Internal to the glTF loader (gltf_loader.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/gltf_detail.h"

namespace so::gltf_detail {

struct GlbChunks {
    const unsigned char* json = nullptr;
    size_t jsonSize = 0;
    std::optional<uint64_t> binSize;
    uint64_t binOffset = 0;  // where the BIN chunk's data starts in the file
};

// Checks the layout more strictly than tinygltf, with messages that say which length is wrong.
GlbChunks glbChunks(const Context& ctx, const std::vector<unsigned char>& d);

// The file as tinygltf is to read it after the extensions rewrote its JSON: the JSON itself for a
// .gltf, a GLB with the new JSON chunk and the file's BIN chunk for a .glb.
std::vector<unsigned char> rewrittenFile(const Json& doc, bool glb, const GlbChunks& chunks,
                                         const std::vector<unsigned char>& file);

}  // namespace so::gltf_detail
