// A glTF file's buffers and bufferViews: the buffer URIs checked, located and size-checked on the
// raw JSON before tinygltf opens anything, image bufferViews checked against the declared buffer
// sizes before tinygltf hands them out, and every bufferView of the loaded model inside its
// buffer. Internal to the glTF loader (gltf_loader.cpp).
#pragma once

#include <cstdint>
#include <optional>

#include "core/gltf_detail.h"

namespace so::gltf_detail {

// `glb`: the file is a GLB, whose BIN chunk (`binSize` bytes, if it has one) is buffer 0's data.
// Adds nothing to ctx.out->bytesRead: it only checks that the files fit the limits.
void checkBuffers(Context& ctx, const Json& doc, bool glb, std::optional<uint64_t> binSize);
// Every image's bufferView inside its buffer's declared byteLength (tinygltf hands the image
// callback a pointer into it unchecked).
void checkImageBufferViews(const Context& ctx, const Json& doc);
// Every bufferView of the loaded model inside its buffer, which checkedAccessor relies on.
void checkBufferViews(const Context& ctx, const tinygltf::Model& model);

}  // namespace so::gltf_detail
