// Safe glTF 2.0 loading on top of tinygltf 2.7 (its known holes:
// tests/data/broken_gltf/expected.tsv).
//
// PUBLIC CONTRACT: traversal order and mesh numbering. Mesh ids in the output images (id.mesh)
// are indices into GltfContent::meshes, so this order must never change silently:
//   * The scene drawn is `scene` if the file sets it, else scenes[0]; a file without scenes draws
//     every root node (a node that is no node's child) in index order.
//   * Nodes are visited depth-first, pre-order, children in the order listed. A node reachable
//     along several paths (instancing) is visited once per path.
//   * World transform = wsFromFile * parent chain * node local, in double; the local transform is
//     `matrix` if given, else T * R * S (the quaternion is normalised).
//   * For each visited node with a mesh, each primitive of that mesh, in order, becomes one
//     MeshPrimitive named "FILE#<node name or nodeN>/<mesh name or meshM>/primK". Triangle lists
//     are kept as is; strips become (i, i+1, i+2) with odd i swapped to (i+1, i, i+2), fans become
//     (0, i+1, i+2). Point and line primitives, and primitives with no triangle, produce no
//     MeshPrimitive (and so no id): they are counted in skippedPrimitives with a warning.
//   * The camera is the first node in that order with a `camera` (if that camera is orthographic,
//     there is no camera, with a warning); lights (KHR_lights_punctual) are listed in that order,
//     one per visit of a node that has one, named after the light and made unique ("_2", "_3"...).
//
// Safety: everything tinygltf would read or we will read is checked first, partly on the raw JSON
// before tinygltf sees it (URIs, GLB chunks, nesting depth, integer ranges, image bufferViews)
// because tinygltf 2.7 either reports those problems vaguely or reads out of bounds on them.
#include "core/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/gltf_alpha.h"
#include "core/gltf_animation_load.h"
#include "core/gltf_detail.h"
#include "core/gltf_draco.h"
#include "core/gltf_extensions.h"
#include "core/gltf_meshopt.h"
#include "core/lights/make_light.h"

namespace so {
namespace {

using namespace gltf_detail;

// tinygltf converts extras and extensions recursively (ParseJsonAsValue), so a deeply nested file
// would overflow the stack. Real files nest fewer than 10 levels.
constexpr int kMaxJsonDepth = 64;

// tinygltf's messages end in newlines and may hold several lines.
std::string oneLine(const std::string& s) {
    std::string joined;
    size_t start = 0;
    while (start < s.size()) {
        size_t end = s.find('\n', start);
        if (end == std::string::npos) end = s.size();
        std::string line = s.substr(start, end - start);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (!line.empty()) joined += (joined.empty() ? "" : "; ") + line;
        start = end + 1;
    }
    return printable(joined, 300);
}

std::vector<std::string> lines(const std::string& s) {
    std::vector<std::string> result;
    size_t start = 0;
    while (start < s.size()) {
        size_t end = s.find('\n', start);
        if (end == std::string::npos) end = s.size();
        std::string line = s.substr(start, end - start);
        if (!line.empty()) result.push_back(printable(line, 200));
        start = end + 1;
    }
    return result;
}

// ---- Files --------------------------------------------------------------------------------------

bool fsFileExists(const std::string& p, void* user) {
    const auto* ctx = static_cast<const Context*>(user);
    std::error_code ec;
    return allowedPath(*ctx, p) && fs::is_regular_file(p, ec);
}

std::string fsExpandFilePath(const std::string& p, void*) {
    return p;
}

bool fsReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& p,
                     void* user) {
    auto* ctx = static_cast<Context*>(user);
    std::string e = allowedPath(*ctx, p) ? readCapped(*ctx, p, *out) : "outside the model's folder";
    if (e.empty()) return true;
    if (ctx->fsError.empty()) {
        ctx->fsField = "buffers";
        ctx->fsError = quoted(p) + ": " + e;
    }
    if (err) *err = e;
    return false;
}

bool fsWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                      void*) {
    if (err) *err = "writing is disabled";
    return false;
}

// Images are not decoded here: the bytes of those stored in the file (bufferView, data: URI) are
// kept, and gltf_alpha.cpp decodes the ones an alpha-tested material uses, through OpenImageIO.
bool keepImageBytes(tinygltf::Image*, const int index, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void* user) {
    auto* ctx = static_cast<Context*>(user);
    if (bytes && size > 0) ctx->embeddedImages[index].assign(bytes, bytes + size);
    return true;
}

// ---- Raw JSON checks, before tinygltf -----------------------------------------------------------

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

// Buffer URIs: checked, located and size-checked here so that errors name the field (tinygltf's
// own messages do not), and nothing outside the folder is ever opened. Image URIs are never
// opened at all (TINYGLTF_NO_EXTERNAL_IMAGE), so an image URI pointing outside the folder, or at a
// missing file, is harmless and not an error.
void checkBuffers(Context& ctx, const Json& doc, bool glb, std::optional<uint64_t> binSize) {
    const Json* buffers = member(doc, "buffers");
    if (!buffers || !buffers->is_array()) return;
    uint64_t planned = ctx.out->bytesRead;
    for (size_t i = 0; i < buffers->size(); ++i) {
        const Json& b = (*buffers)[i];
        std::string field = idx("buffers", i);
        if (!b.is_object()) fail(ctx, field, "not a JSON object");
        const Json* uri = member(b, "uri");
        const Json* len = member(b, "byteLength");
        if (!uri && isMeshoptFallback(b)) {
            // No data: EXT_meshopt_compression decodes into it, so its byteLength is allocated.
            if (!len || !len->is_number_unsigned())
                fail(ctx, field + ".byteLength", "missing (a fallback buffer's size)");
            if (len->get<uint64_t>() > ctx.limits.maxFileBytes)
                fail(ctx, field + ".byteLength",
                     std::to_string(len->get<uint64_t>()) + " bytes, over the limit of " +
                         std::to_string(ctx.limits.maxFileBytes));
            planned += len->get<uint64_t>();
            if (planned > ctx.limits.maxTotalBytes)
                fail(ctx, field + ".byteLength",
                     "buffers total " + std::to_string(planned) + " bytes, over the limit of " +
                         std::to_string(ctx.limits.maxTotalBytes));
            continue;
        }
        if (!uri) {
            // tinygltf would hand the BIN chunk to every buffer without a URI.
            if (!glb || i != 0) fail(ctx, field + ".uri", "missing");
            if (!binSize) fail(ctx, field, "no uri and the GLB file has no BIN chunk");
            if (len && len->is_number_unsigned() && len->get<uint64_t>() > *binSize)
                fail(ctx, field + ".byteLength",
                     std::to_string(len->get<uint64_t>()) + " exceeds the GLB BIN chunk (" +
                         std::to_string(*binSize) + " bytes)");
            continue;
        }
        if (!uri->is_string()) fail(ctx, field + ".uri", "not a string");
        const std::string& s = uri->get_ref<const std::string&>();
        if (s.rfind("data:", 0) == 0) {
            if (!tinygltf::IsDataURI(s))
                fail(ctx, field + ".uri",
                     "unsupported data URI (only base64 application/octet-stream or "
                     "application/gltf-buffer)");
            continue;
        }
        for (const std::string& form : {s, urlDecode(s)}) {
            std::string reason = unsafeUriReason(form);
            if (!reason.empty()) fail(ctx, field + ".uri", quoted(s) + ": " + reason);
        }
        fs::path p = ctx.folderPrefix + urlDecode(s);
        std::error_code ec;
        if (!fs::is_regular_file(p, ec))
            fail(ctx, field + ".uri", quoted(s) + ": file not found (or not a regular file)");
        if (!insideFolder(ctx.canonicalFolder, p))
            fail(ctx, field + ".uri",
                 quoted(s) + ": resolves (through a link) outside the model's folder");
        uint64_t size = fs::file_size(p, ec);
        if (ec) fail(ctx, field + ".uri", quoted(s) + ": cannot get the file size");
        if (size > ctx.limits.maxFileBytes)
            fail(ctx, field + ".uri",
                 quoted(s) + ": file is " + std::to_string(size) + " bytes, over the limit of " +
                     std::to_string(ctx.limits.maxFileBytes));
        planned += size;
        if (planned > ctx.limits.maxTotalBytes)
            fail(ctx, field + ".uri",
                 quoted(s) + ": files read total " + std::to_string(planned) +
                     " bytes, over the limit of " + std::to_string(ctx.limits.maxTotalBytes));
        if (len && len->is_number_unsigned() && len->get<uint64_t>() != size)
            fail(ctx, field + ".byteLength",
                 std::to_string(len->get<uint64_t>()) + " does not match the size of " + quoted(s) +
                     " (" + std::to_string(size) + " bytes)");
    }
}

// tinygltf hands &buffer.data[bufferView.byteOffset] to the image callback without any check,
// so image bufferViews are checked against the declared buffer sizes before it runs (tinygltf
// makes every loaded buffer exactly byteLength long).
void checkImageBufferViews(const Context& ctx, const Json& doc) {
    const Json* images = member(doc, "images");
    if (!images || !images->is_array()) return;
    const Json* views = member(doc, "bufferViews");
    const Json* buffers = member(doc, "buffers");
    for (size_t i = 0; i < images->size(); ++i) {
        const Json* bv = member((*images)[i], "bufferView");
        if (!bv) continue;
        std::string field = idx("images", i) + ".bufferView";
        if (!bv->is_number_integer() || bv->get<int64_t>() < 0 || !views || !views->is_array() ||
            bv->get<uint64_t>() >= views->size())
            fail(ctx, field, "not a valid bufferView index");
        const Json& view = (*views)[bv->get<size_t>()];
        const Json* b = member(view, "buffer");
        if (!b || !b->is_number_integer() || b->get<int64_t>() < 0 || !buffers ||
            !buffers->is_array() || b->get<uint64_t>() >= buffers->size())
            fail(ctx, field, "its bufferView has no valid buffer");
        const Json* len = member((*buffers)[b->get<size_t>()], "byteLength");
        const Json* off = member(view, "byteOffset");
        const Json* vlen = member(view, "byteLength");
        uint64_t o = off && off->is_number_unsigned() ? off->get<uint64_t>() : 0;
        uint64_t l = vlen && vlen->is_number_unsigned() ? vlen->get<uint64_t>() : 0;
        uint64_t end = 0;
        if (!len || !len->is_number_unsigned() || l == 0 || __builtin_add_overflow(o, l, &end) ||
            end > len->get<uint64_t>())
            fail(ctx, field, "its bufferView is empty or outside its buffer");
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

// tinygltf fails the whole load on a bad light with a message that names no light.
void checkLights(const Context& ctx, const Json& doc) {
    const Json* ext = member(doc, "extensions");
    const Json* khr = ext ? member(*ext, "KHR_lights_punctual") : nullptr;
    const Json* lights = khr ? member(*khr, "lights") : nullptr;
    if (!lights) return;
    if (!lights->is_array()) fail(ctx, "KHR_lights_punctual.lights", "not an array");
    for (size_t i = 0; i < lights->size(); ++i) {
        std::string field = "KHR_lights_punctual." + idx("lights", i);
        const Json& l = (*lights)[i];
        const Json* type = member(l, "type");
        if (!type || !type->is_string()) fail(ctx, field + ".type", "missing or not a string");
        const std::string& t = type->get_ref<const std::string&>();
        if (t != "point" && t != "directional" && t != "spot")
            fail(ctx, field + ".type", "unknown light type " + quoted(t));
        if (t == "spot" && !(member(l, "spot") && member(l, "spot")->is_object()))
            fail(ctx, field + ".spot", "a spot light needs a 'spot' object");
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

// ---- GLB container ------------------------------------------------------------------------------

uint32_t readU32(const unsigned char* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

struct GlbChunks {
    const unsigned char* json = nullptr;
    size_t jsonSize = 0;
    std::optional<uint64_t> binSize;
    uint64_t binOffset = 0;  // where the BIN chunk's data starts in the file
};

// Checks the layout more strictly than tinygltf, with messages that say which length is wrong.
GlbChunks glbChunks(const Context& ctx, const std::vector<unsigned char>& d) {
    if (d.size() < 20)
        fail(ctx, "GLB header",
             "file too short for a GLB header (" + std::to_string(d.size()) + " bytes)");
    if (readU32(&d[4]) != 2)
        fail(ctx, "GLB header.version", "unsupported version " + std::to_string(readU32(&d[4])));
    uint64_t length = readU32(&d[8]);
    if (length != d.size())
        fail(ctx, "GLB header.length",
             std::to_string(length) + " does not match the file size " + std::to_string(d.size()) +
                 " (truncated file?)");
    uint64_t jsonLength = readU32(&d[12]);
    if (readU32(&d[16]) != 0x4E4F534Au) fail(ctx, "GLB chunk 0", "first chunk is not JSON");
    if (jsonLength == 0 || 20 + jsonLength > length)
        fail(ctx, "GLB chunk 0.chunkLength",
             std::to_string(jsonLength) + " does not fit the file (" + std::to_string(length - 20) +
                 " bytes after the header)");
    // tinygltf looks for the BIN chunk right after jsonLength bytes, so padding is required.
    if (jsonLength % 4 != 0)
        fail(
            ctx, "GLB chunk 0.chunkLength",
            std::to_string(jsonLength) + " is not a multiple of 4 (the JSON chunk must be padded)");
    GlbChunks c;
    c.json = d.data() + 20;
    c.jsonSize = static_cast<size_t>(jsonLength);
    uint64_t pos = 20 + jsonLength;
    if (pos < length) {
        if (pos + 8 > length) fail(ctx, "GLB chunk 1", "truncated chunk header");
        uint64_t binLength = readU32(&d[pos]);
        if (pos + 8 + binLength > length)
            fail(ctx, "GLB chunk 1.chunkLength",
                 std::to_string(binLength) + " does not fit the file (" +
                     std::to_string(length - pos - 8) + " bytes left)");
        if (readU32(&d[pos + 4]) != 0x004E4942u)
            fail(ctx, "GLB chunk 1", "second chunk is not BIN");
        c.binSize = binLength;
        c.binOffset = pos + 8;
    }
    return c;
}

// The file as tinygltf is to read it after the extensions rewrote its JSON: the JSON itself for a
// .gltf, a GLB with the new JSON chunk and the file's BIN chunk for a .glb.
std::vector<unsigned char> rewrittenFile(const Json& doc, bool glb, const GlbChunks& chunks,
                                         const std::vector<unsigned char>& file) {
    std::string json = doc.dump(-1, ' ', false, Json::error_handler_t::replace);
    if (!glb) return std::vector<unsigned char>(json.begin(), json.end());
    while (json.size() % 4 != 0) json += ' ';
    auto put32 = [](std::vector<unsigned char>& out, uint64_t v) {
        for (int k = 0; k < 4; ++k) out.push_back(static_cast<unsigned char>(v >> (8 * k)));
    };
    // The BIN chunk is copied as the file has it, with its own length.
    const uint64_t binSize = chunks.binSize.value_or(0);
    const uint64_t total = 12 + 8 + json.size() + (chunks.binSize ? 8 + binSize : 0);
    std::vector<unsigned char> out;
    out.reserve(size_t(total));
    out.insert(out.end(), file.begin(), file.begin() + 8);  // magic and version
    put32(out, total);
    put32(out, json.size());
    put32(out, 0x4E4F534Au);
    out.insert(out.end(), json.begin(), json.end());
    if (chunks.binSize) {
        put32(out, binSize);
        put32(out, 0x004E4942u);
        const auto bin = file.begin() + std::ptrdiff_t(chunks.binOffset);
        out.insert(out.end(), bin, bin + std::ptrdiff_t(binSize));
    }
    return out;
}

// ---- Validated access to the loaded model ----------------------------------------------------

void checkBufferViews(const Context& ctx, const tinygltf::Model& model) {
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const tinygltf::BufferView& bv = model.bufferViews[i];
        std::string field = idx("bufferViews", i);
        if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
            fail(ctx, field + ".buffer",
                 std::to_string(bv.buffer) + " out of range (" +
                     std::to_string(model.buffers.size()) + " buffers)");
        uint64_t size = model.buffers[size_t(bv.buffer)].data.size();
        uint64_t end = 0;
        bool overflow =
            __builtin_add_overflow(uint64_t(bv.byteOffset), uint64_t(bv.byteLength), &end);
        if (overflow || end > size)
            fail(ctx, field,
                 "byteOffset + byteLength exceeds " + idx("buffers", size_t(bv.buffer)) +
                     ".byteLength (" + (overflow ? std::string("overflow") : std::to_string(end)) +
                     " > " + std::to_string(size) + ")");
    }
}

bool allFinite(const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

bool allFinite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

glm::dmat4 localTransform(const Context& ctx, const tinygltf::Node& n, size_t i) {
    std::string field = idx("nodes", i);
    auto checkArray = [&](const std::vector<double>& v, size_t want, const char* name) {
        if (v.empty()) return false;
        if (v.size() != want)
            fail(ctx, field + "." + name,
                 "expected " + std::to_string(want) + " numbers, got " + std::to_string(v.size()));
        if (!allFinite(v)) fail(ctx, field + "." + name, "non-finite value");
        return true;
    };
    if (checkArray(n.matrix, 16, "matrix")) {
        glm::dmat4 m(1.0);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c * 4 + r)];
        if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
            fail(ctx, field + ".matrix", "not affine (last row must be 0 0 0 1)");
        return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (checkArray(n.translation, 3, "translation"))
        t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
    if (checkArray(n.rotation, 4, "rotation")) {
        glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
        double len = glm::length(q);
        if (!(len > 0.0) || !std::isfinite(len))
            fail(ctx, field + ".rotation", "zero-length quaternion");
        r = glm::mat4_cast(q / len);
    }
    if (checkArray(n.scale, 3, "scale")) {
        s[0][0] = n.scale[0];
        s[1][1] = n.scale[1];
        s[2][2] = n.scale[2];
    }
    return t * r * s;
}

// Rejects cycles anywhere in the node graph, iteratively (a hostile file must not exhaust the
// stack).
void checkNodeGraph(const Context& ctx, const tinygltf::Model& model) {
    const size_t n = model.nodes.size();
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < model.nodes[i].children.size(); ++c) {
            int child = model.nodes[i].children[c];
            if (child < 0 || size_t(child) >= n)
                fail(ctx, idx("nodes", i) + "." + idx("children", c),
                     std::to_string(child) + " out of range (" + std::to_string(n) + " nodes)");
        }
    enum : char { kNew, kOnPath, kDone };
    std::vector<char> state(n, kNew);
    std::vector<std::pair<size_t, size_t>> stack;  // node, next child
    for (size_t root = 0; root < n; ++root) {
        if (state[root] != kNew) continue;
        stack.push_back({root, 0});
        state[root] = kOnPath;
        while (!stack.empty()) {
            auto& [node, next] = stack.back();
            const auto& children = model.nodes[node].children;
            if (next == children.size()) {
                state[node] = kDone;
                stack.pop_back();
                continue;
            }
            size_t child = size_t(children[next++]);
            if (state[child] == kOnPath)
                fail(ctx, idx("nodes", node) + ".children",
                     "cycle in the node graph (back to " + idx("nodes", child) + ")");
            if (state[child] == kNew) {
                state[child] = kOnPath;
                stack.push_back({child, 0});
            }
        }
    }
}

struct Instance {
    size_t node;
    glm::dmat4 world;
    int64_t link = -1;  // into the ChainLink list, when animations play
};

// The path from a root down to one node instance, one link a visit (a node reached along several
// paths has several), kept only when animations play: a moving primitive's chain is read from it.
struct ChainLink {
    size_t node;
    int64_t parent;  // -1 at a root
    bool moving;     // this node or an ancestor on the path is animated
};

// Calls visit(Instance) in traversal order. Instances are not stored: only what they produce is.
template <typename Visit>
void traverse(const Context& ctx, const tinygltf::Model& model, const Json& doc,
              const glm::dmat4& wsFromFile, std::vector<ChainLink>* links, Visit&& visit) {
    std::vector<int> roots;
    if (model.scenes.empty()) {
        std::vector<char> isChild(model.nodes.size(), 0);
        for (const auto& n : model.nodes)
            for (int c : n.children) isChild[size_t(c)] = 1;
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
    } else {
        if (member(doc, "scene") && model.defaultScene < 0)
            fail(ctx, "scene", "must be a non-negative integer");
        size_t s = model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
        if (s >= model.scenes.size())
            fail(ctx, "scene",
                 std::to_string(s) + " out of range (" + std::to_string(model.scenes.size()) +
                     " scenes)");
        roots = model.scenes[s].nodes;
        for (size_t i = 0; i < roots.size(); ++i)
            if (roots[i] < 0 || size_t(roots[i]) >= model.nodes.size())
                fail(ctx, idx("scenes", s) + "." + idx("nodes", i),
                     std::to_string(roots[i]) + " out of range (" +
                         std::to_string(model.nodes.size()) + " nodes)");
    }
    std::vector<glm::dmat4> local(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        local[i] = localTransform(ctx, model.nodes[i], i);
        // An animated node is drawn as the animation poses it at t = 0.
        if (ctx.animates(i)) local[i] = ctx.animatedNodes[i]->localAt(0.0);
    }

    // Shared subtrees multiply (a chain of nodes each listing the next twice expands to 2^depth
    // instances), so the number of node instances is counted first, in topological order with
    // saturating sums (the graph has no cycle), and bounded like the number of meshes.
    const size_t n = model.nodes.size();
    std::vector<uint64_t> instances(n, 0);
    std::vector<size_t> parents(n, 0);
    for (const auto& node : model.nodes)
        for (int c : node.children) ++parents[size_t(c)];
    for (int r : roots)
        instances[size_t(r)] = std::min<uint64_t>(instances[size_t(r)] + 1, 1ull << 62);
    std::vector<size_t> ready;
    for (size_t i = 0; i < n; ++i)
        if (parents[i] == 0) ready.push_back(i);
    uint64_t total = 0;
    while (!ready.empty()) {
        size_t i = ready.back();
        ready.pop_back();
        total = std::min<uint64_t>(total + instances[i], 1ull << 62);
        for (int c : model.nodes[i].children) {
            instances[size_t(c)] =
                std::min<uint64_t>(instances[size_t(c)] + instances[i], 1ull << 62);
            if (--parents[size_t(c)] == 0) ready.push_back(size_t(c));
        }
    }
    const uint64_t maxInstances = ctx.limits.maxMeshes + n;
    if (total > maxInstances)
        fail(ctx, "nodes",
             "the scene expands to " +
                 (total >= (1ull << 62) ? std::string("over 2^62") : std::to_string(total)) +
                 " node instances, more than " + std::to_string(maxInstances));
    struct Item {
        size_t node;
        int depth;
        glm::dmat4 parent;
        int64_t parentLink;
    };
    std::vector<Item> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
        stack.push_back({size_t(*it), 1, wsFromFile, -1});
    while (!stack.empty()) {
        Item item = stack.back();
        stack.pop_back();
        std::string field = idx("nodes", item.node);
        if (item.depth > ctx.limits.maxNodeDepth)
            fail(ctx, field,
                 "node hierarchy deeper than " + std::to_string(ctx.limits.maxNodeDepth) +
                     " levels");
        glm::dmat4 world = item.parent * local[item.node];
        if (!allFinite(world)) fail(ctx, field, "world transform is not finite");
        int64_t link = -1;
        if (links) {
            const bool parentMoving =
                item.parentLink >= 0 && (*links)[size_t(item.parentLink)].moving;
            links->push_back({item.node, item.parentLink, parentMoving || ctx.animates(item.node)});
            link = int64_t(links->size() - 1);
        }
        visit(Instance{item.node, world, link});
        const auto& children = model.nodes[item.node].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it)
            stack.push_back({size_t(*it), item.depth + 1, world, link});
    }
}

glm::dvec3 unitDirection(const Context& ctx, const glm::dmat4& m, const glm::dvec3& local,
                         const std::string& field) {
    glm::dvec3 d = glm::dvec3(m * glm::dvec4(local, 0.0));
    double len = glm::length(d);
    if (!(len > 0.0) || !std::isfinite(len))
        fail(ctx, field, "transform collapses a direction to zero");
    return d / len;
}

void addCamera(const Context& ctx, const tinygltf::Model& model, const Instance& inst,
               std::optional<CameraDesc>& camera, bool& cameraSeen) {
    const tinygltf::Node& node = model.nodes[inst.node];
    if (node.camera < 0 || cameraSeen) return;
    cameraSeen = true;
    const tinygltf::Camera& cam = model.cameras[size_t(node.camera)];
    std::string field = idx("cameras", size_t(node.camera));
    if (cam.type != "perspective") {
        ctx.out->warnings.push_back(field + ": " + printable(cam.type) +
                                    " camera ignored (only perspective cameras are used)");
        return;
    }
    double yfov = cam.perspective.yfov * 180.0 / std::numbers::pi;
    if (!(yfov > 0.0 && yfov < 180.0))
        fail(ctx, field + ".perspective.yfov", "must be in (0, pi) radians");
    std::string nodeField = idx("nodes", inst.node);
    CameraDesc c;
    c.wsEye = glm::dvec3(inst.world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    c.wsTarget = c.wsEye + unitDirection(ctx, inst.world, {0.0, 0.0, -1.0}, nodeField);
    c.wsUp = unitDirection(ctx, inst.world, {0.0, 1.0, 0.0}, nodeField);
    c.vfovDeg = yfov;
    const double side = std::max(1, ctx.limits.maxImageSide);
    double ar = cam.perspective.aspectRatio;
    // Clamped as doubles: converting an out-of-range double to int is undefined.
    c.height = int(std::min(512.0, side));
    c.width = int(ar > 0.0 ? std::clamp(std::round(512.0 * ar), 1.0, side) : std::min(512.0, side));
    camera = c;
}

void addLight(const Context& ctx, const tinygltf::Model& model, const Instance& inst,
              std::set<std::string>& names) {
    const tinygltf::Node& node = model.nodes[inst.node];
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return;
    std::string field = idx("nodes", inst.node) + ".extensions.KHR_lights_punctual.light";
    const tinygltf::Value& v = ext->second.Get("light");
    if (!v.IsInt()) fail(ctx, field, "missing or not an integer");
    int li = v.Get<int>();
    if (li < 0 || size_t(li) >= model.lights.size())
        fail(ctx, field,
             "light " + std::to_string(li) + " out of range (" +
                 std::to_string(model.lights.size()) + " lights)");
    if (ctx.out->lights.size() >= ctx.limits.maxLights)
        fail(ctx, "KHR_lights_punctual",
             "more than " + std::to_string(ctx.limits.maxLights) + " lights in the scene");
    const tinygltf::Light& src = model.lights[size_t(li)];
    std::string lightField = "KHR_lights_punctual." + idx("lights", size_t(li));
    const glm::dvec3 wsAt(inst.world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    Light l = pointLight("", wsAt);
    if (src.type != "point") {
        // Normalising drops the node's (uniform) scale, which glTF says lights ignore.
        const glm::dvec3 wsAlong =
            unitDirection(ctx, inst.world, {0.0, 0.0, -1.0}, idx("nodes", inst.node));
        if (src.type == "spot") {
            double inner = src.spot.innerConeAngle * 180.0 / std::numbers::pi;
            double outer = src.spot.outerConeAngle * 180.0 / std::numbers::pi;
            if (!(inner >= 0.0 && inner <= outer && outer > 0.0 && outer <= 90.0))
                fail(ctx, lightField + ".spot",
                     "need 0 <= innerConeAngle <= outerConeAngle <= pi/2 and outerConeAngle > 0");
            l = spotLight("", wsAt, wsAlong, outer, inner);
        } else {
            l = directionalLight("", wsAlong);
            l.wsPosition =
                wsAt;  // the node's place, kept as before (a directional light ignores it)
        }
    }
    std::string base = channels::sanitizeLayerName(src.name, "light" + std::to_string(li));
    std::string name = base;
    for (size_t n = 2; names.count(name); ++n) {
        std::string suffix = "_" + std::to_string(n);
        name = base.substr(0, 64 - suffix.size()) + suffix;
    }
    SO_CHECK(channels::isValidLayerName(name));
    names.insert(name);
    l.name = name;
    ctx.out->lights.push_back(std::move(l));
}

struct PlannedPrimitive {
    Instance instance;
    size_t mesh, prim;
    AccessorData positions;
    std::optional<AccessorData> indices;
    int mode;
    uint64_t elements;  // index count, or vertex count when not indexed
    uint64_t triangles;
    std::shared_ptr<MeshAnimation> animation;  // a moving primitive's chain (no positions yet)
};

std::string primField(size_t mesh, size_t prim) {
    return idx("meshes", mesh) + "." + idx("primitives", prim);
}

uint32_t readIndex(const AccessorData& a, uint64_t i) {
    const unsigned char* p = a.base + i * a.stride;
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return p[0];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        default: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
    }
}

// POSITION: VEC3 FLOAT, or with KHR_mesh_quantization VEC3 of (normalized or not) BYTE,
// UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT (the extension's table; the node transform scales them).
void checkPositionType(const Context& ctx, const tinygltf::Accessor& a, size_t index) {
    const bool quantizedType = a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                               a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                               a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
                               a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (a.type == TINYGLTF_TYPE_VEC3 && a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
    if (a.type == TINYGLTF_TYPE_VEC3 && quantizedType && ctx.meshQuantization) return;
    fail(ctx, idx("accessors", index),
         a.type == TINYGLTF_TYPE_VEC3 && quantizedType
             ? "POSITION must be VEC3 FLOAT (integer positions need KHR_mesh_quantization in "
               "extensionsUsed)"
             : "POSITION must be VEC3 FLOAT, or with KHR_mesh_quantization VEC3 BYTE, "
               "UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT");
}

MeshPrimitive build(const Context& ctx, const tinygltf::Model& model, const Json& doc,
                    const PlannedPrimitive& pp, GltfAlpha& alpha) {
    const Instance& inst = pp.instance;
    const tinygltf::Node& node = model.nodes[inst.node];
    const tinygltf::Mesh& mesh = model.meshes[pp.mesh];
    const tinygltf::Primitive& prim = mesh.primitives[pp.prim];
    std::string field = primField(pp.mesh, pp.prim);
    MeshPrimitive out;
    out.name = ctx.displayName + "#" +
               (node.name.empty() ? "node" + std::to_string(inst.node) : printable(node.name)) +
               "/" + (mesh.name.empty() ? "mesh" + std::to_string(pp.mesh) : printable(mesh.name)) +
               "/prim" + std::to_string(pp.prim);

    const std::string posField = idx("accessors", size_t(prim.attributes.at("POSITION")));
    out.wsPositions.resize(size_t(pp.positions.count));
    for (uint64_t i = 0; i < pp.positions.count; ++i) {
        float f[3];
        for (int c = 0; c < 3; ++c) f[c] = readComponent(pp.positions, i, c);
        if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2]))
            fail(ctx, posField, "POSITION " + std::to_string(i) + " is not finite");
        glm::dvec3 p = glm::dvec3(inst.world * glm::dvec4(f[0], f[1], f[2], 1.0));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            fail(ctx, idx("nodes", inst.node),
                 "world position of " + field + " vertex " + std::to_string(i) + " is not finite");
        out.wsPositions[size_t(i)] = p;
    }
    if (pp.animation) {
        auto animation = std::make_shared<MeshAnimation>(*pp.animation);
        animation->lsPositions.resize(size_t(pp.positions.count));
        for (uint64_t i = 0; i < pp.positions.count; ++i)
            for (int c = 0; c < 3; ++c)
                animation->lsPositions[size_t(i)][c] = readComponent(pp.positions, i, c);
        out.animation = std::move(animation);
    }

    std::vector<uint32_t> elements(size_t(pp.elements));
    for (uint64_t i = 0; i < pp.elements; ++i) {
        uint32_t v = pp.indices ? readIndex(*pp.indices, i) : uint32_t(i);
        if (v >= pp.positions.count)
            fail(ctx, field + ".indices",
                 "index " + std::to_string(v) + " (element " + std::to_string(i) +
                     ") >= vertex count " + std::to_string(pp.positions.count));
        elements[size_t(i)] = v;
    }
    if (pp.mode == TINYGLTF_MODE_TRIANGLES) {
        out.indices = std::move(elements);
    } else {
        out.indices.reserve(size_t(pp.triangles) * 3);
        for (size_t i = 0; i < size_t(pp.triangles); ++i) {
            if (pp.mode == TINYGLTF_MODE_TRIANGLE_FAN)
                out.indices.insert(out.indices.end(),
                                   {elements[0], elements[i + 1], elements[i + 2]});
            else if (i % 2 == 0)
                out.indices.insert(out.indices.end(),
                                   {elements[i], elements[i + 1], elements[i + 2]});
            else
                out.indices.insert(out.indices.end(),
                                   {elements[i + 1], elements[i], elements[i + 2]});
        }
    }
    alpha.apply(prim, pp.positions.count, field, out);
    if (prim.material >= 0 && size_t(prim.material) < model.materials.size())
        out.doubleSided = model.materials[size_t(prim.material)].doubleSided;
    // A lightmap's coordinates, when the file has them
    // (raster_compare/gl/lightmaps/lightmap_atlas.h).
    if (auto uv1 = prim.attributes.find("TEXCOORD_1"); uv1 != prim.attributes.end())
        out.lightmapUvs = readTexCoords(ctx, model, doc, uv1->second, "TEXCOORD_1",
                                        pp.positions.count, field, glm::dmat3(1.0));
    return out;
}

// Every node's mesh and camera index in range, before the graph is walked.
void checkNodeIndices(const Context& ctx, const tinygltf::Model& model) {
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& n = model.nodes[i];
        if (n.mesh < -1 || n.mesh >= int(model.meshes.size()))
            fail(ctx, idx("nodes", i) + ".mesh",
                 std::to_string(n.mesh) + " out of range (" + std::to_string(model.meshes.size()) +
                     " meshes)");
        if (n.camera < -1 || n.camera >= int(model.cameras.size()))
            fail(ctx, idx("nodes", i) + ".camera",
                 std::to_string(n.camera) + " out of range (" +
                     std::to_string(model.cameras.size()) + " cameras)");
    }
}

// What the first pass counts besides the plan: the primitives it skips, the totals the limits
// bound, and whether anything animates (ignored, with a warning).
struct PlanCounts {
    size_t nonTriangle = 0, empty = 0;
    uint64_t totalTriangles = 0, totalVertices = 0;
    bool skinsOrMorphs = false;
};

void checkIndexType(const Context& ctx, const tinygltf::Accessor& a, int index,
                    const std::string& field) {
    if (a.type != TINYGLTF_TYPE_SCALAR ||
        (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        fail(ctx, field + ".indices",
             idx("accessors", size_t(index)) +
                 " must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
}

// The triangles a primitive's elements make in its mode (a TRIANGLES count must be a multiple
// of 3).
uint64_t plannedTriangles(const Context& ctx, const PlannedPrimitive& pp,
                          const std::string& field) {
    if (pp.mode != TINYGLTF_MODE_TRIANGLES) return pp.elements < 3 ? 0 : pp.elements - 2;
    if (pp.elements % 3 != 0)
        fail(ctx, field + (pp.indices ? ".indices" : ".attributes.POSITION"),
             "TRIANGLES with " + std::to_string(pp.elements) + " elements, not a multiple of 3");
    return pp.elements / 3;
}

// Primitive k of the instance's mesh, checked and counted: its plan, or nothing for a point, line
// or empty primitive (counted in `counts`).
std::optional<PlannedPrimitive> planPrimitive(const Context& ctx, const tinygltf::Model& model,
                                              const Json& doc, const Instance& inst, size_t k,
                                              PlanCounts& counts) {
    const size_t meshIndex = size_t(model.nodes[inst.node].mesh);
    const tinygltf::Primitive& prim = model.meshes[meshIndex].primitives[k];
    const std::string field = primField(meshIndex, k);
    counts.skinsOrMorphs |= !prim.targets.empty();
    if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
        fail(ctx, field + ".mode", "invalid mode " + std::to_string(prim.mode));
    if (prim.mode < TINYGLTF_MODE_TRIANGLES) {
        ++counts.nonTriangle;
        return std::nullopt;
    }
    PlannedPrimitive pp{inst, meshIndex, k, {}, std::nullopt, prim.mode, 0, 0, nullptr};
    auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) fail(ctx, field + ".attributes", "no POSITION");
    pp.positions = checkedAccessor(
        ctx, model, doc, pos->second, field + ".attributes.POSITION",
        [&](const tinygltf::Accessor& a) { checkPositionType(ctx, a, size_t(pos->second)); });
    if (pp.positions.count > 3 * ctx.limits.maxTrianglesPerMesh)
        fail(ctx, idx("accessors", size_t(pos->second)) + ".count",
             std::to_string(pp.positions.count) + " vertices, over 3 x maxTrianglesPerMesh");
    pp.elements = pp.positions.count;
    if (prim.indices >= 0) {
        pp.indices = checkedAccessor(
            ctx, model, doc, prim.indices, field + ".indices",
            [&](const tinygltf::Accessor& a) { checkIndexType(ctx, a, prim.indices, field); });
        pp.elements = pp.indices->count;
    }
    pp.triangles = plannedTriangles(ctx, pp, field);
    if (pp.triangles == 0) {
        ++counts.empty;
        return std::nullopt;
    }
    if (pp.triangles > ctx.limits.maxTrianglesPerMesh)
        fail(ctx, field,
             std::to_string(pp.triangles) + " triangles, over the limit of " +
                 std::to_string(ctx.limits.maxTrianglesPerMesh));
    return pp;
}

// The limits on the whole scene, checked as each primitive joins the plan, so that nothing is
// allocated past them.
void addToPlan(const Context& ctx, const PlannedPrimitive& pp, std::vector<PlannedPrimitive>& plan,
               PlanCounts& counts) {
    if (plan.size() + 1 > ctx.limits.maxMeshes)
        fail(ctx, "meshes",
             "more than " + std::to_string(ctx.limits.maxMeshes) + " drawn primitives");
    counts.totalTriangles += pp.triangles;
    counts.totalVertices += pp.positions.count;
    if (counts.totalTriangles > ctx.limits.maxTotalTriangles)
        fail(ctx, "meshes",
             "more than " + std::to_string(ctx.limits.maxTotalTriangles) + " triangles in all");
    if (counts.totalVertices > 3 * ctx.limits.maxTotalTriangles)
        fail(ctx, "meshes",
             "more than " + std::to_string(3 * ctx.limits.maxTotalTriangles) + " vertices in all");
    plan.push_back(pp);
}

void planWarnings(const PlanCounts& counts, GltfContent& out) {
    if (counts.nonTriangle > 0)
        out.warnings.push_back(std::to_string(counts.nonTriangle) +
                               " point or line primitive(s) skipped (only triangles are traced)");
    if (counts.empty > 0)
        out.warnings.push_back(std::to_string(counts.empty) +
                               " primitive(s) with no triangle skipped");
    if (counts.skinsOrMorphs)
        out.warnings.push_back("skins and morph targets are ignored (meshes drawn in rest pose)");
    out.skippedPrimitives = counts.nonTriangle + counts.empty;
}

void alphaWarnings(const GltfAlpha& alpha, const tinygltf::Model& model, GltfContent& out) {
    if (!alpha.imagesNotRead().empty()) {
        std::string names;
        size_t listed = 0;
        for (size_t i : alpha.imagesNotRead()) {
            if (listed++ == 4) {
                names += ", and " + std::to_string(alpha.imagesNotRead().size() - 4) + " more";
                break;
            }
            const std::string& uri = model.images[i].uri;
            names += (names.empty() ? "" : ", ") + idx("images", i) +
                     (uri.empty() ? "" : " " + quoted(printable(uri, 60)));
        }
        out.warnings.push_back(std::to_string(alpha.imagesNotRead().size()) +
                               " image(s) of alpha-tested materials not read (effects lacks "
                               "\"alpha\"): " +
                               names);
    }
    if (alpha.fromBlend() > 0)
        out.warnings.push_back(std::to_string(alpha.fromBlend()) +
                               " primitive(s) with alphaMode BLEND read as MASK at cutoff 0.5");
}

// The chain of a node instance under a moving node: every node from its root down, the still
// ones (made once, in `still`) at their own local transform. A skinned mesh there is refused:
// rigid motion would move its bind pose, not what its author animated.
std::shared_ptr<MeshAnimation> meshAnimation(
    const Context& ctx, const tinygltf::Model& model, const std::vector<ChainLink>& links,
    const Instance& inst, const glm::dmat4& wsFromFile,
    std::vector<std::shared_ptr<const AnimatedNode>>& still) {
    if (inst.link < 0 || !links[size_t(inst.link)].moving) return nullptr;
    if (model.nodes[inst.node].skin >= 0)
        fail(ctx, idx("nodes", inst.node) + ".skin",
             "an animation moves this skinned mesh: skinning and morph targets are not supported "
             "yet");
    auto animation = std::make_shared<MeshAnimation>();
    animation->wsFromFile = wsFromFile;
    for (int64_t l = inst.link; l >= 0; l = links[size_t(l)].parent) {
        const size_t node = links[size_t(l)].node;
        if (ctx.animates(node)) {
            animation->chain.push_back(ctx.animatedNodes[node]);
            continue;
        }
        if (!still[node]) {
            auto n = std::make_shared<AnimatedNode>();
            n->restLocal = localTransform(ctx, model.nodes[node], node);
            still[node] = std::move(n);
        }
        animation->chain.push_back(still[node]);
    }
    std::reverse(animation->chain.begin(), animation->chain.end());
    return animation;
}

// A scene with a sequence: the played clips' nodes, and whether the clip named is in the file.
void readAnimations(Context& ctx, const tinygltf::Model& model, const Json& doc) {
    if (!ctx.playAnimations) return;
    GltfContent& out = *ctx.out;
    out.animationNames = animationNames(model);
    out.animationClipFound =
        ctx.animationClip.empty() ||
        std::any_of(model.animations.begin(), model.animations.end(),
                    [&](const tinygltf::Animation& a) { return a.name == ctx.animationClip; });
    ctx.animatedNodes = playedAnimations(ctx, model, doc, ctx.animationClip);
}

void convert(Context& ctx, const tinygltf::Model& model, const Json& doc,
             const glm::dmat4& wsFromFile) {
    GltfContent& out = *ctx.out;
    checkBufferViews(ctx, model);
    checkNodeIndices(ctx, model);
    checkNodeGraph(ctx, model);
    readAnimations(ctx, model, doc);
    std::vector<ChainLink> links;
    std::vector<std::shared_ptr<const AnimatedNode>> stillNodes(model.nodes.size());
    const bool anyMoving = std::any_of(ctx.animatedNodes.begin(), ctx.animatedNodes.end(),
                                       [](const auto& n) { return n != nullptr; });

    // Pass 1: validate and count everything, so that limits are checked before allocating.
    std::vector<PlannedPrimitive> plan;
    PlanCounts counts;
    bool cameraSeen = false;
    std::set<std::string> lightNames;
    traverse(ctx, model, doc, wsFromFile, anyMoving ? &links : nullptr, [&](const Instance& inst) {
        const tinygltf::Node& node = model.nodes[inst.node];
        addCamera(ctx, model, inst, out.camera, cameraSeen);
        addLight(ctx, model, inst, lightNames);
        if (node.mesh < 0) return;
        counts.skinsOrMorphs |= node.skin >= 0 || !node.weights.empty();
        const size_t primitives = model.meshes[size_t(node.mesh)].primitives.size();
        std::shared_ptr<MeshAnimation> animation =
            anyMoving ? meshAnimation(ctx, model, links, inst, wsFromFile, stillNodes) : nullptr;
        for (size_t k = 0; k < primitives; ++k)
            if (std::optional<PlannedPrimitive> pp =
                    planPrimitive(ctx, model, doc, inst, k, counts)) {
                pp->animation = animation;
                addToPlan(ctx, *pp, plan, counts);
            }
    });
    planWarnings(counts, out);

    // Pass 2: build.
    GltfAlpha alpha(ctx, model, doc);
    out.meshes.reserve(plan.size());
    for (const PlannedPrimitive& pp : plan) out.meshes.push_back(build(ctx, model, doc, pp, alpha));
    out.alphaTextures = alpha.takeTextures();
    alphaWarnings(alpha, model, out);
}

// tinygltf's reading of the (checked, possibly rewritten) file; its warnings go to the content.
tinygltf::Model parseWithTinygltf(Context& ctx, const std::vector<unsigned char>& data, bool glb) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keepImageBytes, &ctx);
    loader.SetFsCallbacks(
        {fsFileExists, fsExpandFilePath, fsReadWholeFile, fsWriteWholeFile, &ctx});
    tinygltf::Model model;
    std::string warn, err;
    bool ok =
        glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, data.data(),
                                          static_cast<unsigned int>(data.size()), ctx.folderPrefix)
            : loader.LoadASCIIFromString(&model, &err, &warn,
                                         reinterpret_cast<const char*>(data.data()),
                                         static_cast<unsigned int>(data.size()), ctx.folderPrefix);
    if (!ok) {
        if (!ctx.fsError.empty()) fail(ctx, ctx.fsField, ctx.fsError);
        if (err.find("Spot light description not found") != std::string::npos)
            fail(ctx, "KHR_lights_punctual.lights", oneLine(err));
        fail(ctx, "",
             "invalid glTF: " + (err.empty() ? std::string("unknown error") : oneLine(err)));
    }
    // tinygltf also reports some problems without failing (e.g. a misaligned GLB chunk).
    for (const std::string* text : {&warn, &err})
        for (const std::string& w : lines(*text)) ctx.out->warnings.push_back(w);
    return model;
}

}  // namespace

GltfContent loadGltf(const std::filesystem::path& path, const std::string& displayName,
                     const glm::dmat4& wsFromFile, const LoadLimits& limits, bool readAlphaTextures,
                     const Sequence* sequence) {
    GltfContent content;
    Context ctx;
    ctx.playAnimations = sequence != nullptr;
    if (sequence) ctx.animationClip = sequence->animation;
    ctx.displayName = displayName;
    ctx.limits = limits;
    ctx.readAlphaTextures = readAlphaTextures;
    ctx.out = &content;
    std::error_code ec;
    fs::path folder = fs::absolute(path, ec).lexically_normal().parent_path();
    if (ec) fail(ctx, "", "cannot resolve the path");
    ctx.folderPrefix = folder.string();
    if (ctx.folderPrefix.empty() || ctx.folderPrefix.back() != '/') ctx.folderPrefix += '/';
    ctx.canonicalFolder = fs::weakly_canonical(folder, ec);
    if (ec) fail(ctx, "", "cannot resolve the folder");

    std::vector<unsigned char> data;
    std::string err = readCapped(ctx, path, data);
    if (!err.empty()) fail(ctx, "", err);
    if (data.empty()) fail(ctx, "", "file is empty");
    if (data.size() > std::numeric_limits<uint32_t>::max())
        fail(ctx, "", "file is 4 GiB or more (tinygltf limit)");

    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    const bool glb = data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0;
    if (ext == ".glb" && !glb) fail(ctx, "GLB header", "bad magic (not a binary glTF file)");

    GlbChunks chunks{data.data(), data.size(), std::nullopt};
    if (glb) chunks = glbChunks(ctx, data);
    const unsigned char* json = chunks.json;
    const size_t jsonSize = chunks.jsonSize;

    checkJsonDepth(ctx, json, jsonSize);
    Json doc;
    try {
        doc = Json::parse(json, json + jsonSize);
    } catch (const Json::exception& e) {
        fail(ctx, "", "invalid JSON: " + printable(e.what(), 200));
    }
    if (!doc.is_object()) fail(ctx, "", "not a glTF file (the JSON is not an object)");
    checkNumbers(ctx, doc, "", "", "");
    checkAssetAndViews(ctx, doc);
    checkBuffers(ctx, doc, glb, chunks.binSize);
    checkImageBufferViews(ctx, doc);
    checkLights(ctx, doc);
    checkPrimitivesParse(ctx, doc);
    const GltfExtensions extensions = checkExtensions(ctx, doc);
    ctx.meshQuantization = extensions.meshQuantization;
    content.gltfExtensionsIgnored = extensions.ignored;

    // Draco and meshopt files hold what tinygltf 2.7 refuses (an indices accessor without a
    // bufferView, a buffer without data): it reads a copy of the JSON with those filled in, and
    // the extensions are decoded from the file's own JSON afterwards.
    Json tinyDoc = doc;
    const bool rewritten = prepareDracoJson(ctx, tinyDoc) | prepareMeshoptJson(tinyDoc);
    if (rewritten) data = rewrittenFile(tinyDoc, glb, chunks, data);
    if (data.size() > std::numeric_limits<uint32_t>::max())
        fail(ctx, "", "file is 4 GiB or more (tinygltf limit)");
    tinyDoc = Json();

    tinygltf::Model model = parseWithTinygltf(ctx, data, glb);
    decodeMeshopt(ctx, model, doc);
    decodeDraco(ctx, model, doc);
    convert(ctx, model, doc, wsFromFile);
    return content;
}

}  // namespace so
