// What every command's output shares: the output folder, the provenance block of its JSON files,
// the scene's warnings on stderr and the preview images (one grey scale: core/preview.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image.h"
#include "core/scene.h"
#include "core/tool_info.h"

namespace so {

// The libraries name their options, never the commands' flags; these say a library's InputError
// again with the flag.
// Runs `f`; any InputError it throws becomes the command line's: "command line: FLAG: message".
template <class F>
decltype(auto) asFlag(const std::string& flag, F&& f) {
    try {
        return f();
    } catch (const InputError& e) {
        throwInputError("command line", flag, e.message());
    }
}
// Runs `f`; an InputError on the library's option `field` (e.g. OracleOptions' "verify", in the
// scene's file) keeps its file and names `flag` as its field.
template <class F>
decltype(auto) namingFlag(const std::string& field, const std::string& flag, F&& f) {
    try {
        return f();
    } catch (const InputError& e) {
        if (e.field() != field) throw;
        throwInputError(e.file(), flag, e.message());
    }
}

// Creates the folder (and its parents); an InputError naming --out when it cannot.
std::filesystem::path makeOutputDir(const std::string& dir);

// The scene loader's warnings, one "warning: <file>: <text>" line each on stderr.
void printSceneWarnings(const std::string& scenePath, const Scene& scene);
// Warnings a library call collected (CachedOracle::warnings, GlContext::takeWarnings), one
// "warning: <text>" line each on stderr.
void printWarnings(const std::vector<std::string>& warnings);

// One PNG per light, "<dir>/<light>.png", in the grey scale of core/preview.h (with the light's
// cosine channel when the image has one). Returns the paths written.
std::vector<std::string> writePreviews(const std::filesystem::path& dir, const ChannelImage& image,
                                       const std::vector<Light>& lights);

// The absolute path of the running shadow-oracle (/proc/self/exe): what a sweep starts as child
// processes and names in its Slurm scripts.
std::filesystem::path thisExecutable();

// The file's JSON, or an InputError naming it: "cannot be read (WHAT)" or "invalid JSON: ...".
nlohmann::json readJsonFile(const std::string& path, const std::string& what);
// Writes `j` (indented) to the file, or an InputError naming it.
void writeJsonFile(const std::filesystem::path& path, const nlohmann::json& j);

}  // namespace so
