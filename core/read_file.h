// Reading a whole input file with a bound on its size, so that a huge or endless file (a FIFO,
// /dev/zero) is an InputError naming it, never an allocation as large as the file says.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace so {

// The file's bytes; `display` names it in errors ("no such file", "not a regular file", "file is
// N bytes, limit is M", a short read).
std::string readFileCapped(const std::filesystem::path& path, const std::string& display,
                           uint64_t maxBytes);

}  // namespace so
