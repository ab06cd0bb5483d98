#include "core/gltf_parse.h"

#include <string>
#include <system_error>

namespace so::gltf_detail {
namespace {

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

// tinygltf's filesystem callbacks: only files inside the model's folder are read (within the
// limits), none is written.
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

}  // namespace

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

}  // namespace so::gltf_detail
