// volume-zfail: stencil shadow volumes counted behind the surface (Carmack's reverse; Everitt and
// Kilgard 2002): back faces +1 and front faces -1 where they fail the depth test. The volumes are
// closed by caps (the casting triangles, and the same at infinity), so the count is right with the
// camera anywhere, inside a shadow included; the price is drawing the caps. Alpha-tested casters
// cast opaque shadows: the volumes and their caps are built from whole triangles, and the caps
// are drawn without the alpha test so that they close the sides (docs/techniques.md).
#include "raster_compare/gl/volumes/shadow_volume.h"

namespace so {
namespace {

class VolumeZFail final : public ShadowVolumeTechnique {
  public:
    static Provenance provenance() {
        return {
            "Everitt and Kilgard, \"Practical and Robust Stenciled Shadow Volumes for "
            "Hardware-Accelerated Rendering\", NVIDIA 2002 (z-fail with caps at infinity)",
            Fidelity::Faithful};
    }
    static ParamTable params() { return {}; }
    explicit VolumeZFail(const ParamValues& v) : ShadowVolumeTechnique(v) {}
    bool zFail() const override { return true; }
};

}  // namespace

SO_REGISTER_TECHNIQUE(VolumeZFail, "volume-zfail",
                      "stencil shadow volumes, z-fail: capped volumes counted behind the surface; "
                      "alpha-tested casters cast opaque shadows (volumes are built from whole "
                      "triangles)");

}  // namespace so
