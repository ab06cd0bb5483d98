#include "core/read_file.h"

#include <fstream>

#include "core/error.h"

namespace so {

std::string readFileCapped(const std::filesystem::path& path, const std::string& display,
                           uint64_t maxBytes) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throwInputError(display, "",
                        std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
    uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) throwInputError(display, "", "cannot read its size: " + ec.message());
    if (size > maxBytes)
        throwInputError(
            display, "",
            "file is " + std::to_string(size) + " bytes, limit is " + std::to_string(maxBytes));
    std::ifstream in(path, std::ios::binary);
    if (!in) throwInputError(display, "", "cannot be opened");
    std::string bytes(size, '\0');
    in.read(bytes.data(), std::streamsize(size));
    if (uint64_t(in.gcount()) != size) throwInputError(display, "", "short read");
    return bytes;
}

}  // namespace so
