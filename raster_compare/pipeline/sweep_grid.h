// The parameter grids of a sweep spec (docs/sweep.md, "techniques"): each parameter's values (a
// number, a list, a range, or a method's names), expanded into settings with the last parameter
// varying fastest, and each technique setting validated before any work. Internal to the sweep
// spec's reading (sweep_spec.cpp; sweep_images.cpp expands an "images" entry's grid).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "raster_compare/pipeline/sweep_spec.h"
#include "raster_compare/pipeline/sweep_spec_json.h"

namespace so::sweep_detail {

// The settings of one grid ("params" of a "techniques" or "images" entry), the last parameter
// varying fastest; `before`: the settings of the entries before this one, for the bound.
// `namesAllowed`: a parameter may be a method's names (a technique's; not a renderer's).
std::vector<SweepTask> expandGrid(const Json& entry, const std::string& name,
                                  const std::string& file, const std::string& field, size_t before,
                                  bool namesAllowed);
// The settings of one "techniques" entry, each created (so validated) before any work.
void expandTechnique(const Json& t, size_t ti, const std::string& file,
                     const SettingValidator& validate, std::vector<SweepTask>& settings);

}  // namespace so::sweep_detail
