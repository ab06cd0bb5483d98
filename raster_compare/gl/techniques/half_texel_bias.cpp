// half-texel-bias: basic with our half-texel depth bias (bias=half-texel,
// biases/half_texel_bias.cpp; `oriented-bias` before issue 63, renamed: it is no engine's design).
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(HalfTexelBiasAlias, "half-texel-bias",
                            "the tangent plane's largest rise over half a texel along each map "
                            "axis, plus the depth precision (ours; was oriented-bias)",
                            "basic", {"bias=half-texel"}, {});

}  // namespace so
