// The shadow-volume family (Crow 1977; Heidmann's z-pass, Carmack's z-fail; Everitt and Kilgard
// 2002): per light the volumes of shadow_volume_geometry.h, built once on the CPU, counted in the
// stencil buffer the camera pass's depth comes with, then the scene drawn where the count is 0.
// Exact per pixel up to rasterisation for point, spot (and area lights at their centre) and
// directional lights: the raster path's own exactness baseline.
//
// Alpha-tested casters: a volume is extruded from whole triangles, so the mask cannot cut it; the
// volumes and caps are drawn without the alpha test (docs/techniques.md, "Alpha-tested
// occluders"), while the camera and visibility passes apply it.
//
// The count wraps in 8 bits (GL_INCR_WRAP / GL_DECR_WRAP): correct as long as fewer than 256
// volume faces cover a pixel, which the first frame measures (counts in raster.json).
#pragma once

#include <memory>

#include "raster_compare/gl/technique.h"

namespace so {

class ShadowVolumeTechnique : public Technique {
  public:
    static constexpr const char* kFamily = "shadow volume";
    explicit ShadowVolumeTechnique(const ParamValues& values) : Technique(values) {}
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const final;

    // z-fail (count behind the surface, capped volumes) rather than z-pass.
    virtual bool zFail() const = 0;
    // z-pass: start the count from the number of volumes that contain the eye (else 0).
    virtual bool initialiseCount() const { return false; }
};

}  // namespace so
