// What made a file: every JSON file the tool writes carries it, and EXR headers a short form.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace so {

// {"name": "shadow-oracle", "version": ..., "git_revision": ...}.
nlohmann::json toolJson();
// "<tool version> <git revision>", for EXR attributes.
std::string toolVersionString();

}  // namespace so
