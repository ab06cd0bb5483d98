// KHR_draco_mesh_compression (docs/scene-format.md, "glTF extensions"): a primitive's indices and
// attributes come from one Draco stream in a bufferView instead of from their accessors' own
// bufferViews. tinygltf 2.7 as Debian ships it does not decode Draco, so the loader does it with
// libdraco and hands the rest of the loader plain accessors: each decoded primitive gets a new
// buffer (indices as UNSIGNED_INT, POSITION and TEXCOORD_n as FLOAT) that its accessors are pointed
// at. Internal to the glTF loader.
#pragma once

#include "core/gltf_detail.h"

namespace so::gltf_detail {

// Before tinygltf: checks every primitive's extension object and points the accessors it leaves
// without a bufferView that tinygltf would refuse (a triangle primitive's indices) at the Draco
// bufferView, for decodeDraco to replace. Returns whether `doc` changed.
bool prepareDracoJson(const Context& ctx, Json& doc);

// After tinygltf: decodes every Draco primitive of the file's meshes (`doc` is the file's own JSON)
// and rewrites its accessors into new buffers appended to `model`. Decoded counts must equal the
// accessors' and stay within the limits; a stream that does not decode is an error naming the
// primitive.
void decodeDraco(const Context& ctx, tinygltf::Model& model, const Json& doc);

}  // namespace so::gltf_detail
