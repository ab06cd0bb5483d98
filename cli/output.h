// What every command's output shares: the output folder, the provenance block of its JSON files,
// the scene's warnings on stderr; the JSON files and previews are core's (json_file.h, preview.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image.h"
#include "core/json_file.h"
#include "core/preview.h"
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

// The absolute path of the running shadow-oracle (/proc/self/exe): what a sweep starts as child
// processes and names in its Slurm scripts.
std::filesystem::path thisExecutable();

}  // namespace so
