// oriented-bias: basic with the oriented depth bias (bias=oriented, biases/oriented_bias.cpp).
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(OrientedBiasAlias, "oriented-bias",
                            "oriented depth bias (after FFXVI 2023): the tangent plane's largest "
                            "rise over half a texel along each map axis, plus the depth precision",
                            "basic", {"bias=oriented"}, {});

}  // namespace so
