#include "core/gltf_meshopt.h"

#include <cstring>
#include <set>

#include <meshoptimizer.h>

namespace so::gltf_detail {

namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";

enum class Mode { Attributes, Triangles, Indices };
enum class Filter { None, Octahedral, Quaternion, Exponential };

// One bufferView's extension object, checked against its own rules (the extension's text).
struct Compressed {
    size_t buffer = 0;
    uint64_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
    Mode mode = Mode::Attributes;
    Filter filter = Filter::None;
};

uint64_t unsignedField(const Context& ctx, const Json& ext, const char* key,
                       const std::string& field, bool required) {
    const Json* v = member(ext, key);
    if (!v) {
        if (required) fail(ctx, field + "." + key, "missing");
        return 0;
    }
    if (!v->is_number_unsigned()) fail(ctx, field + "." + key, "must be a non-negative integer");
    return v->get<uint64_t>();
}

std::string stringField(const Context& ctx, const Json& ext, const char* key,
                        const std::string& field, const char* fallback) {
    const Json* v = member(ext, key);
    if (!v) return fallback;
    if (!v->is_string()) fail(ctx, field + "." + key, "not a string");
    return v->get<std::string>();
}

Compressed parse(const Context& ctx, const Json& ext, const std::string& field,
                 size_t bufferCount) {
    if (!ext.is_object()) fail(ctx, field, "not an object");
    Compressed c;
    c.buffer = size_t(unsignedField(ctx, ext, "buffer", field, true));
    if (c.buffer >= bufferCount)
        fail(ctx, field + ".buffer",
             std::to_string(c.buffer) + " out of range (" + std::to_string(bufferCount) +
                 " buffers)");
    c.byteOffset = unsignedField(ctx, ext, "byteOffset", field, false);
    c.byteLength = unsignedField(ctx, ext, "byteLength", field, true);
    c.byteStride = unsignedField(ctx, ext, "byteStride", field, true);
    c.count = unsignedField(ctx, ext, "count", field, true);
    const std::string mode = stringField(ctx, ext, "mode", field, "");
    const std::string filter = stringField(ctx, ext, "filter", field, "NONE");
    if (mode == "ATTRIBUTES")
        c.mode = Mode::Attributes;
    else if (mode == "TRIANGLES")
        c.mode = Mode::Triangles;
    else if (mode == "INDICES")
        c.mode = Mode::Indices;
    else
        fail(ctx, field + ".mode",
             (mode.empty() ? std::string("missing") : printable(mode, 40)) +
                 ": not ATTRIBUTES, TRIANGLES or INDICES");
    if (filter == "NONE")
        c.filter = Filter::None;
    else if (filter == "OCTAHEDRAL")
        c.filter = Filter::Octahedral;
    else if (filter == "QUATERNION")
        c.filter = Filter::Quaternion;
    else if (filter == "EXPONENTIAL")
        c.filter = Filter::Exponential;
    else
        fail(ctx, field + ".filter",
             printable(filter, 40) + ": not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    return c;
}

// The stride and count rules of each mode and filter, which the decoders assume.
void checkShape(const Context& ctx, const Compressed& c, const std::string& field) {
    const uint64_t s = c.byteStride;
    if (c.mode == Mode::Attributes) {
        if (s == 0 || s % 4 != 0 || s > 256)
            fail(ctx, field + ".byteStride",
                 std::to_string(s) + ": ATTRIBUTES needs a multiple of 4 in [4, 256]");
    } else {
        if (s != 2 && s != 4)
            fail(ctx, field + ".byteStride", std::to_string(s) + ": indices need 2 or 4");
        if (c.mode == Mode::Triangles && c.count % 3 != 0)
            fail(ctx, field + ".count",
                 std::to_string(c.count) + ": TRIANGLES needs a multiple of 3");
        if (c.filter != Filter::None)
            fail(ctx, field + ".filter", "only ATTRIBUTES may have a filter");
    }
    const bool strideOk = c.filter == Filter::None ||
                          (c.filter == Filter::Octahedral && (s == 4 || s == 8)) ||
                          (c.filter == Filter::Quaternion && s == 8) ||
                          (c.filter == Filter::Exponential && s % 4 == 0);
    if (!strideOk)
        fail(ctx, field + ".byteStride",
             std::to_string(s) +
                 " does not suit the filter (OCTAHEDRAL: 4 or 8, QUATERNION: 8, "
                 "EXPONENTIAL: a multiple of 4)");
}

// Decodes `c` into `out` (count * byteStride bytes).
int decodeInto(const Compressed& c, const unsigned char* src, std::vector<unsigned char>& out) {
    const size_t count = size_t(c.count), stride = size_t(c.byteStride);
    const size_t size = size_t(c.byteLength);
    int rc = 0;
    if (c.mode == Mode::Attributes)
        rc = meshopt_decodeVertexBuffer(out.data(), count, stride, src, size);
    else if (c.mode == Mode::Triangles)
        rc = meshopt_decodeIndexBuffer(out.data(), count, stride, src, size);
    else
        rc = meshopt_decodeIndexSequence(out.data(), count, stride, src, size);
    if (rc != 0 || count == 0) return rc;
    if (c.filter == Filter::Octahedral) meshopt_decodeFilterOct(out.data(), count, stride);
    if (c.filter == Filter::Quaternion) meshopt_decodeFilterQuat(out.data(), count, stride);
    if (c.filter == Filter::Exponential) meshopt_decodeFilterExp(out.data(), count, stride);
    return 0;
}

// Sizes the fallback buffers to their declared byteLength (their placeholder held a few bytes).
std::set<size_t> sizeFallbacks(tinygltf::Model& model, const Json& doc) {
    std::set<size_t> fallbacks;
    const Json* buffers = member(doc, "buffers");
    if (!buffers || !buffers->is_array()) return fallbacks;
    for (size_t i = 0; i < buffers->size() && i < model.buffers.size(); ++i) {
        const Json& b = (*buffers)[i];
        if (!isMeshoptFallback(b) || member(b, "uri")) continue;
        // checkBuffers has bounded byteLength by the file size limit.
        const Json* len = member(b, "byteLength");
        model.buffers[i].data.assign(len ? len->get<size_t>() : 0, 0);
        fallbacks.insert(i);
    }
    return fallbacks;
}

void decodeView(const Context& ctx, tinygltf::Model& model, size_t i, const Json& ext,
                const std::set<size_t>& fallbacks) {
    const std::string field = idx("bufferViews", i) + ".extensions." + kMeshopt;
    const Compressed c = parse(ctx, ext, field, model.buffers.size());
    checkShape(ctx, c, field);
    if (fallbacks.count(c.buffer))
        fail(ctx, field + ".buffer", "a fallback buffer holds no data to decode");
    const std::vector<unsigned char>& source = model.buffers[c.buffer].data;
    uint64_t end = 0;
    if (__builtin_add_overflow(c.byteOffset, c.byteLength, &end) || end > source.size())
        fail(ctx, field,
             "byteOffset + byteLength exceeds " + idx("buffers", c.buffer) + " (" +
                 std::to_string(source.size()) + " bytes; truncated file?)");
    const tinygltf::BufferView& view = model.bufferViews[i];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        fail(ctx, idx("bufferViews", i) + ".buffer", "out of range");
    std::vector<unsigned char>& target = model.buffers[size_t(view.buffer)].data;
    uint64_t decodedSize = 0, viewEnd = 0;
    if (__builtin_mul_overflow(c.count, c.byteStride, &decodedSize) ||
        decodedSize > view.byteLength)
        fail(ctx, field,
             "count * byteStride exceeds " + idx("bufferViews", i) + ".byteLength (" +
                 std::to_string(view.byteLength) + ")");
    if (__builtin_add_overflow(uint64_t(view.byteOffset), uint64_t(view.byteLength), &viewEnd) ||
        viewEnd > target.size())
        fail(ctx, idx("bufferViews", i),
             "byteOffset + byteLength exceeds " + idx("buffers", size_t(view.buffer)) + " (" +
                 std::to_string(target.size()) + " bytes)");
    // Decoded apart, then copied: the source may lie in the same buffer as the target.
    std::vector<unsigned char> decoded(static_cast<size_t>(decodedSize));
    if (int rc = decodeInto(c, source.data() + c.byteOffset, decoded); rc != 0)
        fail(ctx, field,
             "the compressed stream does not decode (meshoptimizer error " + std::to_string(rc) +
                 ")");
    if (!decoded.empty())
        std::memcpy(target.data() + view.byteOffset, decoded.data(), decoded.size());
}

}  // namespace

bool isMeshoptFallback(const Json& b) {
    const Json* exts = member(b, "extensions");
    const Json* ext = exts ? member(*exts, kMeshopt) : nullptr;
    const Json* fallback = ext ? member(*ext, "fallback") : nullptr;
    return fallback && fallback->is_boolean() && fallback->get<bool>();
}

bool prepareMeshoptJson(Json& doc) {
    bool changed = false;
    if (!doc.contains("buffers") || !doc["buffers"].is_array()) return false;
    for (Json& b : doc["buffers"]) {
        if (!isMeshoptFallback(b) || b.contains("uri")) continue;
        b["uri"] = "data:application/octet-stream;base64,AAAA";  // three zero bytes
        b["byteLength"] = 3;
        changed = true;
    }
    return changed;
}

void decodeMeshopt(const Context& ctx, tinygltf::Model& model, const Json& doc) {
    const Json* views = member(doc, "bufferViews");
    if (!views || !views->is_array()) return;
    const std::set<size_t> fallbacks = sizeFallbacks(model, doc);
    for (size_t i = 0; i < views->size() && i < model.bufferViews.size(); ++i) {
        const Json* exts = member((*views)[i], "extensions");
        if (const Json* ext = exts ? member(*exts, kMeshopt) : nullptr)
            decodeView(ctx, model, i, *ext, fallbacks);
    }
}

}  // namespace so::gltf_detail
