// The JSON files the tool writes and reads back (oracle.json, raster.json, metrics.json, a
// sweep's spec and rows): one reader and one writer, so every file is indented the same way and
// every failure is the same one-line error naming the file.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace so {

// The file's JSON, or an InputError naming it: "cannot be read (WHAT)" or "invalid JSON: ...".
nlohmann::json readJsonFile(const std::string& path, const std::string& what);
// Writes `j` (indented by 2, a newline at the end) to the file, or an InputError naming it.
void writeJsonFile(const std::filesystem::path& path, const nlohmann::json& j);

}  // namespace so
