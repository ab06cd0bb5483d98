// bias: basic with the constant depth bias (bias=constant, biases/constant_bias.cpp), its amount
// under the name it had, `bias`.
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(BiasAlias, "bias",
                            "constant depth bias: lit where receiver depth - bias <= stored depth",
                            "basic", {"bias=constant"}, {{"bias", "depth_texels"}});

}  // namespace so
