#include "cli/output.h"

#include <fstream>
#include <iostream>

#include "core/channels.h"
#include "core/error.h"
#include "core/image_codec.h"
#include "core/preview.h"
#include "core/version.h"

namespace so {

std::filesystem::path makeOutputDir(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwInputError(dir, "--out", "cannot create the folder: " + ec.message());
    return std::filesystem::path(dir);
}

void printWarnings(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
}

void printSceneWarnings(const std::string& scenePath, const Scene& scene) {
    for (const std::string& w : scene.stats.warnings)
        std::cerr << "warning: " << scenePath << ": " << w << "\n";
}

std::vector<std::string> writePreviews(const std::filesystem::path& dir, const ChannelImage& image,
                                       const std::vector<Light>& lights) {
    namespace ch = channels;
    std::vector<std::string> paths;
    for (const Light& light : lights) {
        const std::string cosName = ch::lightChannel(light.name, ch::kCosine);
        const float* V = image.channel(ch::lightChannel(light.name, ch::kVisibility));
        const float* cosine = image.has(cosName) ? image.channel(cosName) : nullptr;
        paths.push_back((dir / (light.name + ".png")).string());
        writePngRgb(paths.back(), image.width(), image.height(), shadowGrey(image, V, cosine));
    }
    return paths;
}

nlohmann::json readJsonFile(const std::string& path, const std::string& what) {
    std::ifstream in(path);
    if (!in) throwInputError(path, "", "cannot be read (" + what + ")");
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throwInputError(path, "", "invalid JSON: " + printable(e.what(), 160));
    }
}

void writeJsonFile(const std::filesystem::path& path, const nlohmann::json& j) {
    std::ofstream out(path);
    if (!out) throwInputError(path.string(), "", "cannot be written");
    out << j.dump(2) << "\n";
}

std::filesystem::path thisExecutable() {
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find this program's path: " + ec.message());
    return p;
}

}  // namespace so
