#include "core/gltf_json_checks.h"

#include <cstdint>
#include <limits>
#include <set>
#include <string>

namespace so::gltf_detail {
namespace {

// tinygltf converts extras and extensions recursively (ParseJsonAsValue), so a deeply nested file
// would overflow the stack. Real files nest fewer than 10 levels.
constexpr int kMaxJsonDepth = 64;

bool isSizeKey(const std::string& k) {
    return k == "byteOffset" || k == "byteLength" || k == "count" || k == "byteStride";
}

// Properties tinygltf reads with GetInt, which wraps 4294967296 to 0.
bool isIntKey(const std::string& k) {
    static const std::set<std::string> keys = {"buffer",    "bufferView",
                                               "mesh",      "camera",
                                               "skin",      "children",
                                               "nodes",     "scene",
                                               "indices",   "material",
                                               "mode",      "index",
                                               "source",    "sampler",
                                               "light",     "node",
                                               "texCoord",  "skeleton",
                                               "joints",    "input",
                                               "output",    "inverseBindMatrices",
                                               "magFilter", "minFilter",
                                               "wrapS",     "wrapT"};
    return keys.count(k) > 0;
}

}  // namespace

void checkJsonDepth(const Context& ctx, const unsigned char* p, size_t n) {
    int depth = 0;
    bool inString = false;
    for (size_t i = 0; i < n; ++i) {
        unsigned char c = p[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth)
                fail(ctx, "",
                     "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

// tinygltf reads sizes as size_t but ignores a negative or fractional optional one (treating
// "byteOffset": -4 as 0), and reads indices as int, wrapping 4294967296 to 0: both would silently
// draw the wrong data, so they are rejected here with the JSON path.
void checkNumbers(const Context& ctx, const Json& j, const std::string& path,
                  const std::string& key, const std::string& parentKey) {
    if (j.is_object()) {
        // Other extensions are not interpreted, so their numbers cannot mislead.
        if (key == "extras" || (parentKey == "extensions" && key != "KHR_lights_punctual")) return;
        for (auto it = j.begin(); it != j.end(); ++it) {
            const std::string& k = it.key();
            std::string sub = path.empty() ? k : path + "." + k;
            if (isSizeKey(k) && !it.value().is_number_unsigned())
                fail(ctx, printable(sub, 120), "must be a non-negative integer");
            checkNumbers(ctx, it.value(), sub, k, key);
        }
    } else if (j.is_array()) {
        for (size_t i = 0; i < j.size(); ++i)
            checkNumbers(ctx, j[i], path + "[" + std::to_string(i) + "]", key, parentKey);
    } else if (j.is_number_integer() &&
               (isIntKey(key) || parentKey == "attributes" || parentKey == "targets")) {
        bool fits = j.is_number_unsigned()
                        ? j.get<uint64_t>() <= uint64_t(std::numeric_limits<int32_t>::max())
                        : j.get<int64_t>() >= std::numeric_limits<int32_t>::min();
        if (!fits) fail(ctx, printable(path, 120), "integer out of range");
    }
}

// tinygltf's messages for these name no field.
void checkAssetAndViews(const Context& ctx, const Json& doc) {
    const Json* asset = member(doc, "asset");
    const Json* version = asset ? member(*asset, "version") : nullptr;
    if (!version || !version->is_string())
        fail(ctx, "asset.version", "missing (not a glTF 2.0 file?)");
    if (version->get_ref<const std::string&>().rfind("2.", 0) != 0)
        fail(ctx, "asset.version",
             "unsupported glTF version " + quoted(version->get_ref<const std::string&>()));
    const Json* views = member(doc, "bufferViews");
    if (!views || !views->is_array()) return;
    for (size_t i = 0; i < views->size(); ++i) {
        const Json* stride = member((*views)[i], "byteStride");
        if (!stride) continue;
        uint64_t v = stride->get<uint64_t>();  // checkNumbers made it unsigned
        if (v < 4 || v > 252 || v % 4 != 0)
            fail(ctx, idx("bufferViews", i) + ".byteStride",
                 std::to_string(v) + " must be a multiple of 4 in [4, 252]");
    }
}

// tinygltf silently drops a primitive it cannot parse, which would renumber the meshes after it.
void checkPrimitivesParse(const Context& ctx, const Json& doc) {
    const Json* meshes = member(doc, "meshes");
    if (!meshes || !meshes->is_array()) return;
    for (size_t m = 0; m < meshes->size(); ++m) {
        const Json* prims = member((*meshes)[m], "primitives");
        if (!prims) continue;
        if (!prims->is_array()) fail(ctx, idx("meshes", m) + ".primitives", "not an array");
        for (size_t k = 0; k < prims->size(); ++k) {
            const Json* attrs = member((*prims)[k], "attributes");
            if (!attrs || !attrs->is_object())
                fail(ctx, idx("meshes", m) + "." + idx("primitives", k) + ".attributes",
                     "missing or not an object");
        }
    }
}

}  // namespace so::gltf_detail
