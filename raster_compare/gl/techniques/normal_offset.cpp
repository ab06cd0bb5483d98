// normal-offset: basic with the normal offset (bias=normal-offset, biases/normal_offset_bias.cpp),
// its parameters under the names they had, `k` and `bias`.
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(NormalOffsetAlias, "normal-offset",
                            "lookup moved along the normal by k texels (1 - n.l)", "basic",
                            {"bias=normal-offset"},
                            {{"k", "normal_texels"}, {"bias", "normal_depth_texels"}});

}  // namespace so
