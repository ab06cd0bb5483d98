// receiver-plane: basic with the receiver plane depth bias (bias=receiver-plane,
// biases/receiver_plane_bias.cpp).
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(ReceiverPlaneAlias, "receiver-plane",
                            "receiver plane depth bias (Isidoro 2006): the depth gradient from "
                            "screen-space derivatives, less the plane's rise over a texel "
                            "(TheRealMJP/Shadows' margin, uncapped)",
                            "basic", {"bias=receiver-plane"}, {});

}  // namespace so
