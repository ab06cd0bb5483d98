#include "cli/output.h"

#include <iostream>

#include "core/error.h"

namespace so {

void printWarnings(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
}

void printSceneWarnings(const std::string& scenePath, const Scene& scene) {
    for (const std::string& w : scene.stats.warnings)
        std::cerr << "warning: " << scenePath << ": " << w << "\n";
}

std::filesystem::path thisExecutable() {
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find this program's path: " + ec.message());
    return p;
}

}  // namespace so
