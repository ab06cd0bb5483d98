// back-faces: basic with the back faces in the map (bias=back-faces, biases/back_faces_bias.cpp),
// its constant bias under the name it had, `bias`.
#include "raster_compare/gl/technique.h"

namespace so {

SO_REGISTER_TECHNIQUE_ALIAS(BackFacesAlias, "back-faces",
                            "back faces in the map (front-face culling), n.l <= 0 is shadow; "
                            "closed meshes only: a single-sided occluder casts nothing",
                            "basic", {"bias=back-faces"}, {{"bias", "back_depth_texels"}});

}  // namespace so
