// contact=on|off, contact_steps, contact_thickness, contact_distance (docs/techniques.md#contact):
// screen-space contact shadows on every technique of the shadow-map family. Per pixel a ray from
// the receiver toward the light, contact_distance long, is marched in contact_steps steps; each
// step is projected into the camera pass's image and compared with the surface the camera saw
// there, which is taken to be contact_thickness thick. A step behind that surface (and behind its
// tangent plane) shadows the pixel; V is the map's V and this one's by the minimum. The method is
// Bend Studio's (Days Gone) as Bevy 0.19 ships it; the defaults are Bevy's ContactShadows::default
// (bevyengine/bevy, crates/bevy_pbr/src/contact_shadows.rs: linear_steps 16, thickness 0.1 m,
// length 0.3 m), lengths in the scene's world units. Shared by every shadow-map technique, as
// TemporalTaps is by pcf and pcss.
#pragma once

#include <string>

#include <epoxy/gl.h>

#include "raster_compare/gl/params.h"

namespace so {

class CameraPass;
struct LocalFrame;

struct ContactShadows {
    // contact (off, on), contact_steps, contact_thickness, contact_distance; the last three need
    // contact=on (ParamSpec::needs).
    static ParamTable params();
    explicit ContactShadows(const ParamValues& values);
    // "#define CONTACT\n", CONTACT_STEPS and the camera pass's texel sizes when on (the march's
    // SO_TAPs), else nothing: off compiles the very shader it did before.
    std::string defines(const CameraPass& camera) const;
    // The march's uniforms (lengths in local units) and its texture units; nothing when off.
    void setUniforms(GLuint program, const LocalFrame& frame) const;
    // Binds the camera pass's position and normal images to the march's units (when on).
    void bindCameraImages(const CameraPass& camera) const;

    bool on = false;
    int steps = 16;
    double wsThickness = 0.1, wsDistance = 0.3;
};

}  // namespace so
