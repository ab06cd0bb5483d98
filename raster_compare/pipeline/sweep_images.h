// The "images" entries of a sweep spec (docs/sweep.md): a renderer's images, one per setting of
// its grid and scene it covers, found through the entry's path pattern ({scene}, {PARAM}) and
// judged as compare --image judges them. Internal to the sweep spec's reading (sweep_spec.cpp);
// the staleness of an image task's row (imageRowIsStale) is sweep_spec.h's.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "raster_compare/pipeline/sweep_spec.h"
#include "raster_compare/pipeline/sweep_spec_json.h"

namespace so::sweep_detail {

// The tasks of one "images" entry (`ii`), per scene it covers, each image present; `before`: the
// tasks of the techniques, for the bound. `validate` tells a built-in technique's name, refused.
void expandImages(const Json& entry, size_t ii, const SweepPlan& plan, const std::string& file,
                  const SettingValidator& validate, size_t before, std::vector<SweepTask>& tasks);

}  // namespace so::sweep_detail
