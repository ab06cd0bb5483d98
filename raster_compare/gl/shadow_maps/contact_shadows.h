// contact=on|off and contact_method=bevy|bend|guarded (docs/techniques.md#contact): screen-space
// contact shadows on every technique of the shadow-map family. Per pixel a march toward the light
// through what the camera saw darkens the map's V (V = the map's times the march's, as Bevy
// multiplies it into its shadow term). Three designs, each in its own GLSL file:
//   bevy (the default): Bevy 0.19's (PR 22382), its SSR ray marcher reused
//     (shaders/contact_bevy.glsl): contact_steps screen-space linear steps along a world ray
//     contact_distance long, jittered per pixel and frame, occluded only below both the point and
//     the bilinear depth, thickness contact_thickness in linear view depth, a soft result by
//     penetration. The default because it is what an engine user gets on every light type: Bevy
//     applies it to point, spot and directional lights alike, where Godot 4.7's port of Bend's is
//     for directional lights only.
//   bend: Bend Studio's screen-space shadows (Days Gone; bend_sss_gpu.h, Godot 4.7 follows it)
//     (shaders/contact_bend.glsl): contact_samples pixel steps toward the light's projected
//     position, a surface thickness relative to depth, a bilinear edge threshold, a contrast, hard
//     then averaged then fading samples.
//   guarded: our own world-unit march with a fixed world thickness, binary, that guards a mesh's
//     own surface with the camera pass's mesh ids (shaders/contact_guarded.glsl): data no engine
//     has; it hides the self-shadowing engine users see.
// bevy and bend read the depth buffer alone: the camera pass's depth, as each pixel's position
// gives it (contact_depth.glsl). Shared by every shadow-map technique, as TemporalTaps is by pcf.
#pragma once

#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "raster_compare/gl/params.h"

namespace so {

class CameraPass;
struct LocalFrame;

enum class ContactMethod { Bevy = 0, Bend = 1, Guarded = 2 };

// Bend's tuning (bend_sss_gpu.h's DispatchParameters and its four compile-time counts).
struct BendContactSettings {
    int samples = 60, hardSamples = 4, fadeSamples = 8;
    double surfaceThickness = 0.005, bilinearThreshold = 0.02, contrast = 4.0;
    bool ignoreEdgePixels = false;
};

struct ContactShadows {
    // contact (off, on), contact_method (needs contact=on), the methods' own parameters (each
    // needs its method: ParamSpec::needs, which chains to contact=on).
    static ParamTable params();
    explicit ContactShadows(const ParamValues& values);
    // "#define CONTACT\n", the method's counts and the camera pass's texel sizes when on (the
    // march's SO_TAPs), else nothing: off compiles the very shader it did before.
    std::string defines(const CameraPass& camera) const;
    // The method's GLSL files, to follow the technique's file (none when off).
    std::vector<const char*> sources() const;
    // The march's uniforms (lengths in local units) and its texture units; nothing when off.
    void setUniforms(GLuint program, const LocalFrame& frame) const;
    // Binds the camera pass's images the method reads to its units (when on).
    void bindCameraImages(const CameraPass& camera) const;

    bool on = false;
    ContactMethod method = ContactMethod::Bevy;
    // bevy and guarded.
    int steps = 16;
    double wsThickness = 0.1, wsDistance = 0.3;
    // bend.
    BendContactSettings bend;
};

}  // namespace so
