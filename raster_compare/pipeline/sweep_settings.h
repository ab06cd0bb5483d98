// What every task of a sweep shares (SweepSettings, docs/sweep.md): the image size and the
// raster and comparison options at the spec's top level, its "oracle" block, "keep_outputs".
// Internal to the sweep spec's reading (sweep_spec.cpp, and sweep_plan_file.cpp for a plan read
// back).
#pragma once

#include <set>
#include <string>

#include "raster_compare/pipeline/sweep_spec.h"
#include "raster_compare/pipeline/sweep_spec_json.h"

namespace so::sweep_detail {

// The spec's top-level keys: its own, the image size and the tables' sweep rows.
std::set<std::string> topLevelKeys();
// The spec's settings, each checked by its option table's row (an InputError naming its field).
SweepSettings parseSettings(const Json& spec, const std::string& file);

}  // namespace so::sweep_detail
