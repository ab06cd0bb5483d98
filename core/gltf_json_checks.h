// The checks on a glTF file's raw JSON that run before tinygltf reads it: nesting depth, the
// numbers tinygltf would misread, the asset version and bufferView strides, and primitives it would
// drop. tinygltf 2.7 reports those problems vaguely, or misreads them silently; these name the
// field. Internal to the glTF loader (gltf_loader.cpp).
#pragma once

#include <cstddef>

#include "core/gltf_detail.h"

namespace so::gltf_detail {

// Refuses JSON nested deeper than tinygltf's recursive conversion can take.
void checkJsonDepth(const Context& ctx, const unsigned char* p, size_t n);
// Sizes must be non-negative integers and indices must fit an int32, anywhere in the document but
// in extras and uninterpreted extensions. `path`, `key` and `parentKey` are "" at the root.
void checkNumbers(const Context& ctx, const Json& j, const std::string& path,
                  const std::string& key, const std::string& parentKey);
// asset.version is 2.x; every bufferViews[i].byteStride a multiple of 4 in [4, 252].
void checkAssetAndViews(const Context& ctx, const Json& doc);
// Every primitive has an attributes object (tinygltf would drop it and renumber the meshes).
void checkPrimitivesParse(const Context& ctx, const Json& doc);

}  // namespace so::gltf_detail
