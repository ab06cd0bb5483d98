// The libraries name their options, never a command's flags; these say a library's InputError again
// in the caller's words (a flag such as --technique), so a command's errors name what its user
// typed. The command line and the pipeline's callers that take a command's options (compareScene,
// the sweep's tasks) share them.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "raster_compare/gl/technique.h"

namespace so {

// Runs `f`; any InputError it throws becomes one of the caller's options: "SOURCE: FLAG: message"
// (the command's "command line: --technique: ...").
template <class F>
decltype(auto) asFlag(const std::string& source, const std::string& flag, F&& f) {
    try {
        return f();
    } catch (const InputError& e) {
        throwInputError(source, flag, e.message());
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

// Creates the folder (and its parents); an InputError naming `flag` (the caller's name of the
// folder's option: the command's "--out") when it cannot.
std::filesystem::path makeOutputDir(const std::string& dir, const std::string& flag);

// The technique an option of the caller names, created (so its settings validated): an unknown
// name is an InputError naming the option as the caller does ("command line: --technique: unknown
// technique "nope" ...").
std::unique_ptr<Technique> createTechniqueOfFlag(const std::string& source, const std::string& flag,
                                                 const std::string& name,
                                                 const std::vector<std::string>& settings);

}  // namespace so
