#include "core/gltf_glb.h"

#include <string>

namespace so::gltf_detail {
namespace {

uint32_t readU32(const unsigned char* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

}  // namespace

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

}  // namespace so::gltf_detail
