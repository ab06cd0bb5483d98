#include "core/gltf_buffers.h"

#include <string>
#include <system_error>

#include "core/gltf_meshopt.h"

namespace so::gltf_detail {

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

}  // namespace so::gltf_detail
