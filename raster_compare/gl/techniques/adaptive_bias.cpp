// adaptive-bias: basic with the adaptive depth bias (bias=adaptive, biases/adaptive_bias.cpp).
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(
    AdaptiveBiasAlias, "adaptive-bias",
    "adaptive depth bias (Dou et al. 2014): the tangent plane's depth where the light's ray "
    "through the texel's centre meets it, less the depth precision",
    "basic", {"bias=adaptive"}, {});

}  // namespace so
