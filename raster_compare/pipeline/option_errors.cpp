#include "raster_compare/pipeline/option_errors.h"

namespace so {

std::filesystem::path makeOutputDir(const std::string& dir, const std::string& flag) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwInputError(dir, flag, "cannot create the folder: " + ec.message());
    return std::filesystem::path(dir);
}

std::unique_ptr<Technique> createTechniqueOfFlag(const std::string& source, const std::string& flag,
                                                 const std::string& name,
                                                 const std::vector<std::string>& settings) {
    asFlag(source, flag, [&] { findTechnique(name); });
    return createTechnique(name, settings);
}

}  // namespace so
