// The comparison options: how compare judges the techniques against the oracle
// (core/option_table.h), the single source of their defaults (the comparison structs' initialisers
// take the constants below, which the rows use), their checks on every surface (`compare`'s
// options, the API's CompareOptions, the sweep spec's top-level keys), of
// `shadow-oracle compare-options` and of docs/cli.md's table. raster_compare/pipeline/
// compare_scene.h writes checked values into CompareOptions; CompareOptionTable.* holds the API's
// and Python's spelling of the defaults to the rows.
#pragma once

#include <span>
#include <string>

#include "core/option_table.h"

namespace so {

inline constexpr int kDefaultBoundaryRadius = 2;  // r of docs/metrics.md, in pixels
// compare --converge N: the most still frames (docs/limits.md); a bound on the run's time, which
// grows as N renders of every technique.
inline constexpr int kMaxConvergeFrames = 256;

const OptionTable& compareOptionTable();
// The row of `key`; std::invalid_argument for a key not in the table (a bug, not input).
const OptionSpec& compareOption(const std::string& key);

}  // namespace so
