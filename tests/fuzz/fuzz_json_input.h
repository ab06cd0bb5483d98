// For the harnesses of JSON readers: parses like the commands do (cli/gate_command.cpp readJson,
// index_page.cpp readSceneMetrics), where invalid JSON becomes an InputError before the reader
// runs.
#pragma once

#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

namespace so::fuzz {

inline std::optional<nlohmann::json> parseJson(std::string_view text) {
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;  // the command reports "invalid JSON" as an InputError
    }
}

}  // namespace so::fuzz
