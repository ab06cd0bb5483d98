// EXT_meshopt_compression (docs/scene-format.md, "glTF extensions"): a bufferView's bytes are
// stored compressed in another buffer range (meshoptimizer's vertex and index codecs, with an
// optional filter), and its own buffer may be a "fallback" that has no data at all. The loader
// decodes each such bufferView with libmeshoptimizer into its own range before any accessor is
// read, so the rest of the loader sees plain bytes. Internal to the glTF loader.
#pragma once

#include <vector>

#include "core/gltf_detail.h"

namespace so::gltf_detail {

// Whether buffer `b` (a JSON buffer object) is a fallback buffer (EXT_meshopt_compression's
// `fallback`: true), which may have no uri and then no data.
bool isMeshoptFallback(const Json& b);

// Before tinygltf: gives every fallback buffer without a uri a placeholder of a few bytes, which
// tinygltf loads in place of the data it would refuse to find. Returns whether `doc` changed.
bool prepareMeshoptJson(Json& doc);

// After tinygltf: sizes each fallback buffer to its declared byteLength (checked against the
// limits by the loader) and decodes every compressed bufferView into it; `doc` is the file's own
// JSON. A stream that does not decode, or fields that do not fit, are errors naming the bufferView.
void decodeMeshopt(const Context& ctx, tinygltf::Model& model, const Json& doc);

}  // namespace so::gltf_detail
