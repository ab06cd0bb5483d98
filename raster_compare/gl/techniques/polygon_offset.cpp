// polygon-offset: basic with glPolygonOffset in the map pass (bias=polygon-offset,
// biases/polygon_offset_bias.cpp).
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(
    PolygonOffsetAlias, "polygon-offset",
    "fixed-function glPolygonOffset in the shadow pass (driver-defined units)", "basic",
    {"bias=polygon-offset"}, {});

}  // namespace so
