#include "core/channels.h"

namespace so::channels {

std::string lightChannel(const std::string& lightName, const char* suffix) {
    return lightName + "." + suffix;
}

const std::vector<std::string>& geometryChannels() {
    static const std::vector<std::string> names = {kHit, kPX, kPY,    kPZ,     kNX,
                                                   kNY,  kNZ, kDepth, kMeshId, kPrimId};
    return names;
}

static bool isReserved(const std::string& name) {
    return name == "P" || name == "N" || name == "id" || name == "A" || name == "Z";
}

static bool isNameChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
}

bool isValidLayerName(const std::string& name) {
    if (name.empty() || name.size() > 64 || isReserved(name)) return false;
    char c0 = name[0];
    if (!((c0 >= 'a' && c0 <= 'z') || (c0 >= 'A' && c0 <= 'Z') || c0 == '_')) return false;
    for (char c : name)
        if (!isNameChar(c)) return false;
    return true;
}

std::string sanitizeLayerName(const std::string& name, const std::string& fallback) {
    std::string out;
    for (char c : name) {
        if (out.size() >= 60) break;
        out += isNameChar(c) ? c : '_';
    }
    if (out.empty()) out = fallback;
    if (!((out[0] >= 'a' && out[0] <= 'z') || (out[0] >= 'A' && out[0] <= 'Z') || out[0] == '_') ||
        isReserved(out))
        out = "L_" + out;
    if (out.size() > 64) out.resize(64);
    return out;
}

}  // namespace so::channels
