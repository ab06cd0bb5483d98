// `shadow-oracle techniques`: the listing of raster_compare/gl/technique_listing.h on stdout.
#pragma once

#include "raster_compare/gl/technique_listing.h"

namespace so {

int runTechniquesCommand(ListingFormat format);

}  // namespace so
