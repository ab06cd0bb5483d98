// The parts of the glTF loader (gltf_loader.cpp) that the loading of alpha-tested materials
// (gltf_alpha.cpp) shares: the load's context, errors naming the field, the folder rules for
// files, and checked accessors. Internal to core/.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

// Must match tinygltf_impl.cpp so that the declarations (Model, TinyGLTF) are the same.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "core/error.h"
#include "core/gltf_animation.h"
#include "core/gltf_loader.h"

namespace so::gltf_detail {

namespace fs = std::filesystem;
using Json = nlohmann::json;

struct Context {
    std::string displayName;
    LoadLimits limits;
    GltfContent* out = nullptr;
    std::string folderPrefix;  // absolute folder of the glTF file, ending in '/'
    fs::path canonicalFolder;
    // Set by the filesystem callbacks, which cannot throw through tinygltf's C-style interface.
    std::string fsField, fsError;
    // Bytes of images stored in the file (bufferView or data: URI), by image index, as tinygltf
    // hands them to its image callback (gltf_alpha.cpp decodes those that masks use).
    std::map<int, std::vector<unsigned char>> embeddedImages;
    // Whether alpha-tested materials' textures are read and decoded: only when the scene's
    // effects include "alpha" (a scene that draws them opaque needs no image, nor its files).
    bool readAlphaTextures = true;
    // KHR_mesh_quantization is used: POSITION and TEXCOORD_n may be integers (normalized or not).
    bool meshQuantization = false;
    // A scene with a sequence plays the file's animations (gltf_animation_load.h): the clip named
    // (empty: every clip), and, once read, the nodes they move by node index (null: a still node).
    bool playAnimations = false;
    std::string animationClip;
    std::vector<std::shared_ptr<const AnimatedNode>> animatedNodes;
    bool animates(size_t node) const { return node < animatedNodes.size() && animatedNodes[node]; }
};

[[noreturn]] void fail(const Context& ctx, const std::string& field, const std::string& message);
std::string idx(const char* array, size_t i);
std::string quoted(const std::string& s);
// Exactly what tinygltf's dlib::urldecode does, so that the path checked is the path opened.
std::string urlDecode(const std::string& s);
// Why a URI may not be opened, or "" if it is a plain relative path inside the folder.
std::string unsafeUriReason(const std::string& uri);
bool insideFolder(const fs::path& canonicalFolder, const fs::path& p);
// Reads a whole regular file, refusing it before reading if it is over the limits. Returns an
// error text, or "" on success; counts the bytes and records the file for the content hash.
std::string readCapped(Context& ctx, const fs::path& p, std::vector<unsigned char>& data);
// tinygltf asks for files as base_dir + "/" + decoded URI: only that form, with a safe relative
// part inside the folder, is ever answered.
bool allowedPath(const Context& ctx, const std::string& p);
const Json* member(const Json& j, const char* key);

struct AccessorData {
    const unsigned char* base = nullptr;
    uint64_t stride = 0;
    uint64_t count = 0;
    int componentType = 0;
    bool normalized = false;
};

uint64_t componentSize(int componentType);
uint64_t componentCount(int type);
// Component `c` of element `i` as a float: a FLOAT as stored; a normalized integer by glTF's
// formulas (unsigned c / (2^n - 1), signed max(c / (2^(n-1) - 1), -1)); any other integer as its
// value (KHR_mesh_quantization's non-normalized attributes, which the node transform scales).
float readComponent(const AccessorData& a, uint64_t i, int c);

// `usedAs` names the reference (e.g. "meshes[0].primitives[1].indices") for range errors.
// `checkType` runs before the byte range is checked, so a wrong type is reported as such rather
// than as a range error computed with the wrong element size.
template <typename CheckType>
AccessorData checkedAccessor(const Context& ctx, const tinygltf::Model& model, const Json& doc,
                             int index, const std::string& usedAs, CheckType&& checkType) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        fail(ctx, usedAs,
             "accessor " + std::to_string(index) + " out of range (" +
                 std::to_string(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    std::string field = idx("accessors", size_t(index));
    const Json* accessors = member(doc, "accessors");
    if (a.sparse.isSparse ||
        (accessors && accessors->is_array() && size_t(index) < accessors->size() &&
         member((*accessors)[size_t(index)], "sparse")))
        fail(ctx, field + ".sparse", "sparse accessors are not supported");
    checkType(a);
    if (a.bufferView < 0)
        fail(ctx, field, "accessors without a bufferView (all zeros) are not supported");
    if (size_t(a.bufferView) >= model.bufferViews.size())
        fail(ctx, field + ".bufferView",
             std::to_string(a.bufferView) + " out of range (" +
                 std::to_string(model.bufferViews.size()) + " bufferViews)");
    if (a.count == 0) fail(ctx, field + ".count", "must be at least 1");
    const tinygltf::BufferView& bv = model.bufferViews[size_t(a.bufferView)];
    std::string bvField = idx("bufferViews", size_t(a.bufferView));
    uint64_t elementSize = componentSize(a.componentType) * componentCount(a.type);
    if (elementSize == 0) fail(ctx, field, "invalid componentType or type");
    uint64_t stride = bv.byteStride == 0 ? elementSize : uint64_t(bv.byteStride);
    // tinygltf has already required byteStride % 4 == 0 and <= 252.
    if (bv.byteStride != 0 && (stride < elementSize || stride > 252 || stride % 4 != 0))
        fail(ctx, bvField + ".byteStride",
             std::to_string(bv.byteStride) + " must be a multiple of 4 in [" +
                 std::to_string(elementSize) + ", 252] for " + field);
    uint64_t span = 0, end = 0;
    bool overflow = __builtin_mul_overflow(stride, uint64_t(a.count - 1), &span) ||
                    __builtin_add_overflow(span, uint64_t(a.byteOffset), &end) ||
                    __builtin_add_overflow(end, elementSize, &end);
    if (overflow || end > bv.byteLength)
        fail(ctx, field,
             "byteOffset + stride*(count-1) + elementSize exceeds " + bvField + ".byteLength (" +
                 (overflow ? std::string("overflows 64 bits") : std::to_string(end)) + " > " +
                 std::to_string(bv.byteLength) + ")");
    // checkBufferViews has put the whole bufferView inside its buffer.
    AccessorData d;
    d.base = model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + a.byteOffset;
    d.stride = stride;
    d.count = a.count;
    d.componentType = a.componentType;
    d.normalized = a.normalized;
    return d;
}

// The primitive's TEXCOORD_n (`name`, at accessor `accessor`): VEC2 FLOAT, or normalized
// UNSIGNED_BYTE or UNSIGNED_SHORT (with KHR_mesh_quantization also normalized BYTE or SHORT and
// the four non-normalized), one per vertex, each finite after `uvFromFile` (the texture's
// KHR_texture_transform; the identity for a lightmap's). `field` names the primitive in errors
// ("meshes[i].primitives[k]").
std::vector<glm::vec2> readTexCoords(const Context& ctx, const tinygltf::Model& model,
                                     const Json& doc, int accessor, const std::string& name,
                                     uint64_t vertexCount, const std::string& field,
                                     const glm::dmat3& uvFromFile);

}  // namespace so::gltf_detail
