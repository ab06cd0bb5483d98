// volume-zpass: stencil shadow volumes counted in front of the surface (Heidmann 1991): +1 where
// the eye's ray enters a volume before reaching the surface, -1 where it leaves. Needs no caps,
// but the count must start from the number of volumes the eye is in (init_count=1: counted on the
// CPU, occluder triangles between the eye and the light); with init_count=0, the naive z-pass, a
// camera inside a shadow inverts it. Volumes clipped by the near plane are not counted either way.
// Alpha-tested casters: the volumes are built from whole triangles, so the caster is opaque in
// them, but the camera pass sees the receiver through its holes, and z-pass, which relies on the
// caster to hide where the eye's ray enters its volume, then misses that entry: V there is
// inverted (lit inside the caster's shadow, shadowed outside it; docs/techniques.md).
#include "raster_compare/gl/volumes/shadow_volume.h"

namespace so {
namespace {

class VolumeZPass final : public ShadowVolumeTechnique {
  public:
    static Provenance provenance() {
        return {
            "Heidmann, \"Real Shadows, Real Time\", IRIS Universe 18, 1991 (z-pass stencil "
            "counting)",
            Fidelity::Faithful};
    }
    static ParamTable params() {
        return {methodParam("init_count", 1, {"zero", "eye"},
                            "eye: start the count at the volumes containing the eye (CPU); zero: "
                            "at 0 (naive)")};
    }
    explicit VolumeZPass(const ParamValues& v)
        : ShadowVolumeTechnique(v), initCount_(v.integer("init_count") == 1) {}
    bool zFail() const override { return false; }
    bool initialiseCount() const override { return initCount_; }

  private:
    bool initCount_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(VolumeZPass, "volume-zpass",
                      "stencil shadow volumes, z-pass: faces in front of the surface counted; "
                      "alpha-tested casters are opaque in the volumes, but a receiver the camera "
                      "sees through a caster's holes gets the count inverted (the entry through "
                      "the caster is missed)");

}  // namespace so
