#include "core/gltf_detail.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

namespace so::gltf_detail {

[[noreturn]] void fail(const Context& ctx, const std::string& field, const std::string& message) {
    throwInputError(ctx.displayName, field, message);
}

std::string idx(const char* array, size_t i) {
    return std::string(array) + "[" + std::to_string(i) + "]";
}

std::string quoted(const std::string& s) {
    return "'" + printable(s) + "'";
}

// Exactly what tinygltf's dlib::urldecode does, so that the path checked is the path opened.
std::string urlDecode(const std::string& s) {
    auto hex = [](unsigned char c) -> unsigned char {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '+') {
            out += ' ';
        } else if (s[i] == '%' && s.size() > i + 2) {
            out += static_cast<char>((hex(static_cast<unsigned char>(s[i + 1])) << 4) |
                                     hex(static_cast<unsigned char>(s[i + 2])));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

// Why a URI may not be opened, or "" if it is a plain relative path inside the folder.
std::string unsafeUriReason(const std::string& uri) {
    if (uri.empty()) return "empty URI";
    for (unsigned char c : uri)
        if (c < 0x20 || c == 0x7f) return "control characters in URI";
    if (uri[0] == '/' || uri[0] == '\\') return "absolute paths are not allowed";
    // A scheme ("http:", "file:", also a drive letter "C:") comes before the first '/'.
    size_t colon = uri.find(':');
    if (colon != std::string::npos && colon < uri.find_first_of("/\\"))
        return "URI scheme '" + printable(uri.substr(0, colon + 1), 20) +
               "' is not allowed (only relative paths inside the model's folder, or base64 data: "
               "URIs)";
    size_t start = 0;
    while (start <= uri.size()) {
        size_t end = uri.find_first_of("/\\", start);
        if (end == std::string::npos) end = uri.size();
        if (uri.compare(start, end - start, "..") == 0 && end - start == 2)
            return "'..' is not allowed (files must be inside the model's folder)";
        start = end + 1;
    }
    return "";
}

bool insideFolder(const fs::path& canonicalFolder, const fs::path& p) {
    std::error_code ec;
    fs::path c = fs::weakly_canonical(p, ec);
    if (ec) return false;
    fs::path rel = c.lexically_relative(canonicalFolder);
    return !rel.empty() && *rel.begin() != ".." && !rel.is_absolute();
}

// Reads a whole regular file, refusing it before reading if it is over the limits. Returns an
// error text, or "" on success.
std::string readCapped(Context& ctx, const fs::path& p, std::vector<unsigned char>& data) {
    std::error_code ec;
    // A FIFO or device could block or never end: only regular files are opened.
    if (!fs::is_regular_file(p, ec)) return "not found or not a regular file";
    uint64_t size = fs::file_size(p, ec);
    if (ec) return "cannot get the file size";
    if (size > ctx.limits.maxFileBytes)
        return "file is " + std::to_string(size) + " bytes, over the limit of " +
               std::to_string(ctx.limits.maxFileBytes);
    if (ctx.out->bytesRead + size > ctx.limits.maxTotalBytes)
        return "files read total " + std::to_string(ctx.out->bytesRead + size) +
               " bytes, over the limit of " + std::to_string(ctx.limits.maxTotalBytes);
    std::ifstream in(p, std::ios::binary);
    if (!in) return "cannot open";
    data.resize(static_cast<size_t>(size));
    if (size > 0) in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(size));
    if (!in || static_cast<uint64_t>(in.gcount()) != size) return "read error (file changed?)";
    ctx.out->filesRead.push_back(p);
    ctx.out->bytesRead += size;
    return "";
}

// tinygltf asks for files as base_dir + "/" + decoded URI (and, failing that, relative to the
// working directory): only the first form, with a safe relative part, is ever answered.
bool allowedPath(const Context& ctx, const std::string& p) {
    if (p.size() <= ctx.folderPrefix.size() ||
        p.compare(0, ctx.folderPrefix.size(), ctx.folderPrefix) != 0)
        return false;
    if (!unsafeUriReason(p.substr(ctx.folderPrefix.size())).empty()) return false;
    return insideFolder(ctx.canonicalFolder, p);
}

const Json* member(const Json& j, const char* key) {
    if (!j.is_object()) return nullptr;
    auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
}

uint64_t componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            return 8;
        default:
            return 0;
    }
}

uint64_t componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        case TINYGLTF_TYPE_MAT2:
            return 4;
        case TINYGLTF_TYPE_MAT3:
            return 9;
        case TINYGLTF_TYPE_MAT4:
            return 16;
        default:
            return 0;
    }
}

float readComponent(const AccessorData& a, uint64_t i, int c) {
    const unsigned char* p = a.base + i * a.stride;
    // glTF 2.0, "Animations" / KHR_mesh_quantization: the normalized integer to float formulas.
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const int8_t v = static_cast<int8_t>(p[c]);
            return a.normalized ? std::max(float(v) / 127.0f, -1.0f) : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return a.normalized ? float(p[c]) / 255.0f : float(p[c]);
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p + 2 * c, 2);
            return a.normalized ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p + 2 * c, 2);
            return a.normalized ? float(v) / 65535.0f : float(v);
        }
        default: {
            float v;
            std::memcpy(&v, p + 4 * c, 4);
            return v;
        }
    }
}

std::vector<glm::vec2> readTexCoords(const Context& ctx, const tinygltf::Model& model,
                                     const Json& doc, int accessor, const std::string& name,
                                     uint64_t vertexCount, const std::string& field,
                                     const glm::dmat3& uvFromFile) {
    const std::string aField = field + ".attributes." + name;
    const AccessorData a =
        checkedAccessor(ctx, model, doc, accessor, aField, [&](const tinygltf::Accessor& acc) {
            const int t = acc.componentType;
            const bool unsignedInt = t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                     t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
            const bool signedInt =
                t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_SHORT;
            const bool core = t == TINYGLTF_COMPONENT_TYPE_FLOAT || (unsignedInt && acc.normalized);
            const bool quantized = ctx.meshQuantization && (unsignedInt || signedInt);
            if (acc.type != TINYGLTF_TYPE_VEC2 || !(core || quantized))
                fail(ctx, idx("accessors", size_t(accessor)),
                     name +
                         " must be VEC2 FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT "
                         "(other BYTE and SHORT forms need KHR_mesh_quantization)");
        });
    if (a.count != vertexCount)
        fail(ctx, aField,
             std::to_string(a.count) + " texture coordinates for " + std::to_string(vertexCount) +
                 " vertices");
    std::vector<glm::vec2> uvs(size_t(a.count));
    for (uint64_t i = 0; i < a.count; ++i) {
        const glm::dvec3 uv(readComponent(a, i, 0), readComponent(a, i, 1), 1.0);
        const glm::dvec3 t = uvFromFile * uv;
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y) || !std::isfinite(float(t.x)) ||
            !std::isfinite(float(t.y)))
            fail(ctx, aField, name + " " + std::to_string(i) + " is not finite");
        uvs[size_t(i)] = glm::vec2(t);
    }
    return uvs;
}

}  // namespace so::gltf_detail
