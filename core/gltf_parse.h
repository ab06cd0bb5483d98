// tinygltf's reading of a checked glTF file, with our filesystem callbacks (files only inside the
// model's folder, within the limits, never written) and an image callback that keeps embedded
// image bytes undecoded. Internal to the glTF loader (gltf_loader.cpp).
#pragma once

#include <vector>

#include "core/gltf_detail.h"

namespace so::gltf_detail {

// tinygltf's reading of the (checked, possibly rewritten) file; its warnings go to the content.
// Throws InputError naming the field where it can (a buffer file refused, a bad spot light).
tinygltf::Model parseWithTinygltf(Context& ctx, const std::vector<unsigned char>& data, bool glb);

}  // namespace so::gltf_detail
