#include "core/json_file.h"

#include <fstream>

#include "core/error.h"

namespace so {

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

}  // namespace so
