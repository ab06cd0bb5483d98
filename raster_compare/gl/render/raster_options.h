// The raster option table's values (core/raster_option_table.h) written into RasterOptions: what
// the command line, the API and the sweep spec each give, checked by the table and applied by one
// function, so that every surface means the same by a key.
#pragma once

#include <string>
#include <vector>

#include "core/raster_option_table.h"
#include "raster_compare/gl/render/renderer.h"

namespace so {

// Checks each of `values` (naming its field as `naming` says) and writes it into `o`.
void applyRasterOptions(const OptionValues& values, const OptionNaming& naming, RasterOptions& o);

// The keys applyRasterOptions can write, sorted (a test compares them with the table's).
std::vector<std::string> appliedRasterOptionKeys();

}  // namespace so
