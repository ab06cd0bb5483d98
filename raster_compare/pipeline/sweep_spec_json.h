// The values of a sweep spec (docs/sweep.md), read through the one reader of user JSON
// (core/json_reader.h) so that its errors read like every other file's, and the spec's bounds.
// Internal to the sweep spec's reading (sweep_spec.cpp, sweep_settings.cpp, sweep_grid.cpp,
// sweep_images.cpp, sweep_plan_file.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "core/option_table.h"

namespace so::sweep_detail {

// The spec is an ordered_json: its settings keep the file's order.
using Json = nlohmann::ordered_json;

// A spec is small; anything larger is not one (and must not be read whole).
constexpr uintmax_t kMaxSpecBytes = 4u << 20;
constexpr size_t kMaxValuesPerParam = 100000;

// The spec's value as plain JSON, what core/json_reader.h reads.
nlohmann::json plain(const Json& v);
// Every key of `obj` (an object, or an error naming `field`) is one of `allowed`.
void checkKeys(const Json& obj, const std::set<std::string>& allowed, const std::string& file,
               const std::string& field);
double number(const Json& v, const std::string& file, const std::string& field);
int integer(const Json& v, const std::string& file, const std::string& field, int lo, int hi);
bool boolean(const Json& v, const std::string& file, const std::string& field);
std::string string(const Json& v, const std::string& file, const std::string& field);
// One option of the spec (core/option_table.h), checked by its table's row.
OptionValue optionValue(const OptionSpec& spec, const Json& v, const std::string& file,
                        const std::string& field);

}  // namespace so::sweep_detail
