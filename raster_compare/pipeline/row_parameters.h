// Typed parameters where a row is made (result_row.h): metrics.json writes a method parameter as
// its index, so the technique's parameter table (ParamSpec::names) names it here, once, for
// compare's rows and a sweep's merged rows alike. Nothing downstream maps an index back to a name.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/compare/result_row.h"

namespace so {

// `value` of parameter `name` of `technique`, typed: a method's name where the technique's table
// names its values, else as paramValueOfJson reads it. An unknown technique (an image's
// "external") or parameter keeps the JSON's kind.
ParamValue typedParamValue(const std::string& technique, const std::string& name,
                           const nlohmann::json& value);

// Every parameter of metrics.json's `parameters` object, typed.
RowParameters typedParameters(const std::string& technique, const nlohmann::json& parameters);

}  // namespace so
