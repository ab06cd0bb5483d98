// slope-bias: basic with the slope-scaled bias (bias=slope, biases/slope_bias.cpp).
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(SlopeBiasAlias, "slope-bias",
                            "slope-scaled bias clamp(slope_factor tan(acos(n.l)), min, max)",
                            "basic", {"bias=slope"}, {});

}  // namespace so
