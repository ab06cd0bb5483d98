#include "raster_compare/gl/shadow_maps/contact_shadows.h"

#include "core/local_frame.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/shaders.h"

namespace so {

namespace {

// Texture units of the march: the family's visibility pass binds only its map, at unit 0.
constexpr int kPositionUnit = 6, kNormalUnit = 7;

// Where the defaults come from. Bevy: bevyengine/bevy at 4805ca79 (0.19, PR 22382). Bend: Bend
// Studio's bend_sss_gpu.h v1.3 (Sony Interactive Entertainment 2023, Apache-2.0), line numbers as
// vendored unchanged in PanosK92/SpartanEngine 516d17e4d, data/shaders/bend_sss_gpu.hlsl.
Provenance bevyProvenance() {
    return {
        "Bevy 0.19 (PR 22382): crates/bevy_pbr/src/render/pbr_functions.wesl "
        "(calculate_contact_shadow) over crates/bevy_pbr/src/ssr/raymarch.wesl "
        "(depth_ray_march_march), defaults ContactShadows::default (contact_shadows.rs)",
        Fidelity::Variant,
        {"each depth is recomputed from the surface point the camera pass stored (16 bytes a "
         "read, counted so in the work) where Bevy samples its 4-byte depth buffer: the same "
         "depth up to float rounding"}};
}

Provenance bendProvenance() {
    return {
        "Bend Studio screen-space shadows v1.3 (Sony Interactive Entertainment 2023): "
        "bend_sss_gpu.h (WriteScreenSpaceShadow, DispatchParameters::SetDefaults), "
        "bend_sss_cpu.h (BuildDispatchList); Godot 4.7 follows it (PR 118045)",
        Fidelity::Variant,
        {"a fragment shader marches each pixel's own ray through its centre, where Bend's "
         "compute wavefront shares one ray among 64 pixels through LDS (that ray passes "
         "within a pixel of each centre, so the minor-axis read positions differ by under a "
         "pixel)"}};
}

Provenance guardedProvenance() {
    return {
        "shadow-oracle's own (issue 54): world-unit steps with Bevy 0.19's defaults, a world "
        "thickness along the camera ray and a mesh-id guard against self-shadowing",
        Fidelity::Own};
}

ParamSpec contactParam(ParamSpec s, const char* needs) {
    s.needs = needs;
    return s;
}

// bevy and guarded: Bevy's three settings (contact_shadows.rs:53-55).
void addMarchParams(ParamTable& table) {
    const char* needs = "contact_method=bevy|guarded";
    table.push_back(contactParam({"contact_steps", 16, 1, 256, true,
                                  "bevy, guarded: samples along the contact ray (Bevy's "
                                  "linear_steps, contact_shadows.rs:53)"},
                                 needs));
    table.push_back(contactParam({"contact_thickness", 0.1, 0.0, 1e6, false,
                                  "bevy, guarded: the thickness assumed behind every surface the "
                                  "camera sees, world units (bevy: in linear view depth; Bevy's "
                                  "thickness, contact_shadows.rs:54)"},
                                 needs));
    table.push_back(contactParam({"contact_distance", 0.3, 0.0, 1e6, false,
                                  "bevy, guarded: the contact ray's length toward the light, world "
                                  "units (Bevy's length, contact_shadows.rs:55)"},
                                 needs));
}

// bend: bend_sss_gpu.h's recommended counts (38, 48, 52) and SetDefaults (127-130).
void addBendParams(ParamTable& table) {
    const char* needs = "contact_method=bend";
    table.push_back(contactParam({"contact_samples", 60, 1, 512, true,
                                  "bend: pixel steps toward the light, the shadow's reach in "
                                  "pixels (SAMPLE_COUNT, bend_sss_gpu.h:38)"},
                                 needs));
    table.push_back(contactParam({"contact_hard_samples", 4, 0, 512, true,
                                  "bend: the first samples, each able to shadow alone "
                                  "(HARD_SHADOW_SAMPLES, bend_sss_gpu.h:48)"},
                                 needs));
    table.push_back(contactParam({"contact_fade_samples", 8, 0, 512, true,
                                  "bend: the last samples, fading out (FADE_OUT_SAMPLES, "
                                  "bend_sss_gpu.h:52)"},
                                 needs));
    table.push_back(contactParam({"contact_surface_thickness", 0.005, 1e-6, 1.0, false,
                                  "bend: the thickness of every pixel, a fraction of its depth "
                                  "to the far plane (SurfaceThickness, bend_sss_gpu.h:127)"},
                                 needs));
    table.push_back(contactParam({"contact_bilinear_threshold", 0.02, 0.0, 1e6, false,
                                  "bend: depth step, a fraction of depth, above which two "
                                  "neighbours are an edge and not interpolated "
                                  "(BilinearThreshold, bend_sss_gpu.h:128)"},
                                 needs));
    table.push_back(contactParam({"contact_contrast", 4, 1, 1e6, false,
                                  "bend: contrast boost of the transition into shadow "
                                  "(ShadowContrast, bend_sss_gpu.h:129)"},
                                 needs));
    ParamSpec ignore = methodParam("contact_ignore_edges", 0, {"off", "on"},
                                   "bend: on, an edge pixel casts no shadow (IgnoreEdgePixels, "
                                   "bend_sss_gpu.h:130)");
    table.push_back(contactParam(std::move(ignore), needs));
}

}  // namespace

ParamTable ContactShadows::params() {
    ParamTable table = {methodParam("contact", 0, {"off", "on"},
                                    "on: screen-space contact shadows (a march toward the light "
                                    "through the camera's depth), V the map's times theirs "
                                    "(docs/techniques.md#contact)")};
    ParamSpec method = methodParam("contact_method", 0, {"bevy", "bend", "guarded"},
                                   "contact=on: whose design (docs/techniques.md#contact): Bevy "
                                   "0.19's, Bend Studio's, or our mesh-id guarded march");
    method.needs = "contact=on";
    method.provenances = {bevyProvenance(), bendProvenance(), guardedProvenance()};
    table.push_back(std::move(method));
    addMarchParams(table);
    addBendParams(table);
    return table;
}

ContactShadows::ContactShadows(const ParamValues& v)
    : on(v.integer("contact") == 1),
      method(ContactMethod(v.integer("contact_method"))),
      steps(v.integer("contact_steps")),
      wsThickness(v.real("contact_thickness")),
      wsDistance(v.real("contact_distance")),
      bend{v.integer("contact_samples"),          v.integer("contact_hard_samples"),
           v.integer("contact_fade_samples"),     v.real("contact_surface_thickness"),
           v.real("contact_bilinear_threshold"),  v.real("contact_contrast"),
           v.integer("contact_ignore_edges") == 1} {}

std::string ContactShadows::defines(const CameraPass& camera) const {
    if (!on) return "";
    std::string d = "#define CONTACT\n#define CONTACT_STEPS " + std::to_string(steps) + "\n";
    if (method == ContactMethod::Bend)
        d += "#define CONTACT_SAMPLES " + std::to_string(bend.samples) +
             "\n#define CONTACT_HARD_SAMPLES " + std::to_string(bend.hardSamples) +
             "\n#define CONTACT_FADE_SAMPLES " + std::to_string(bend.fadeSamples) + "\n" +
             (bend.ignoreEdgePixels ? "#define CONTACT_IGNORE_EDGES\n" : "");
    return d + camera.texelBytesDefines();
}

std::vector<const char*> ContactShadows::sources() const {
    if (!on) return {};
    switch (method) {
        case ContactMethod::Bevy:
            return {shaders::contact_depth_glsl, shaders::contact_bevy_glsl};
        case ContactMethod::Bend:
            return {shaders::contact_depth_glsl, shaders::contact_bend_glsl};
        case ContactMethod::Guarded:
            break;
    }
    return {shaders::contact_guarded_glsl};
}

void ContactShadows::setUniforms(GLuint program, const LocalFrame& frame) const {
    if (!on) return;
    setInt(program, "u_contactPosition", kPositionUnit);
    if (method == ContactMethod::Bend) {
        setFloat(program, "u_contactSurfaceThickness", bend.surfaceThickness);
        setFloat(program, "u_contactBilinearThreshold", bend.bilinearThreshold);
        setFloat(program, "u_contactContrast", bend.contrast);
        return;
    }
    // Bevy compares its thickness in view depth, which the camera's matrix keeps in world units.
    setFloat(program, "u_contactThickness",
             method == ContactMethod::Bevy ? wsThickness : frame.lsLength(wsThickness));
    setFloat(program, "u_contactDistance", frame.lsLength(wsDistance));
    if (method == ContactMethod::Guarded) setInt(program, "u_contactNormal", kNormalUnit);
}

void ContactShadows::bindCameraImages(const CameraPass& camera) const {
    if (!on) return;
    glBindTextureUnit(kPositionUnit, camera.positionTexture());
    if (method == ContactMethod::Guarded) glBindTextureUnit(kNormalUnit, camera.normalTexture());
}

}  // namespace so
