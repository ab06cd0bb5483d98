// The raster options: how the raster path times a render (core/option_table.h), the single source
// of their defaults (RasterOptions' initialisers take the constants below, which the rows use),
// their checks on every surface (`raster` and `compare`'s options, the API's RenderOptions and
// CompareOptions, the sweep spec's top-level keys), of `shadow-oracle raster-options` and of
// docs/cli.md's table. raster_compare/gl/render/raster_options.h writes checked values into
// RasterOptions; RasterOptionTable.* holds the API's and Python's spelling of the defaults to the
// rows.
#pragma once

#include <span>
#include <string>

#include "core/option_table.h"

namespace so {

inline constexpr int kDefaultFrames = 9;  // timed frames
inline constexpr int kDefaultWarmup = 2;  // untimed frames before them

const OptionTable& rasterOptionTable();
// The row of `key`; std::invalid_argument for a key not in the table (a bug, not input).
const OptionSpec& rasterOption(const std::string& key);

}  // namespace so
