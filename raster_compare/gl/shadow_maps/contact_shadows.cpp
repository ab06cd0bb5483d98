#include "raster_compare/gl/shadow_maps/contact_shadows.h"

#include "core/local_frame.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"

namespace so {

namespace {
// Texture units of the march: the family's visibility pass binds only its map, at unit 0.
constexpr int kPositionUnit = 6, kNormalUnit = 7;
}  // namespace

ParamTable ContactShadows::params() {
    ParamSpec steps = {"contact_steps",
                       16,
                       1,
                       256,
                       true,
                       "contact=on: samples along the contact ray (Bevy's linear_steps)"};
    ParamSpec thickness = {"contact_thickness",
                           0.1,
                           0.0,
                           1e6,
                           false,
                           "contact=on: the thickness assumed behind every surface the camera "
                           "sees, world units"};
    ParamSpec distance = {"contact_distance",
                          0.3,
                          0.0,
                          1e6,
                          false,
                          "contact=on: the contact ray's length toward the light, world units"};
    for (ParamSpec* s : {&steps, &thickness, &distance}) s->needs = "contact=on";
    return {methodParam("contact", 0, {"off", "on"},
                        "on: screen-space contact shadows (a march toward the light through the "
                        "camera's depth), V the minimum of the map's and theirs "
                        "(docs/techniques.md#contact)"),
            steps, thickness, distance};
}

ContactShadows::ContactShadows(const ParamValues& v)
    : on(v.integer("contact") == 1),
      steps(v.integer("contact_steps")),
      wsThickness(v.real("contact_thickness")),
      wsDistance(v.real("contact_distance")) {}

std::string ContactShadows::defines(const CameraPass& camera) const {
    if (!on) return "";
    return "#define CONTACT\n#define CONTACT_STEPS " + std::to_string(steps) + "\n" +
           camera.texelBytesDefines();
}

void ContactShadows::setUniforms(GLuint program, const LocalFrame& frame) const {
    if (!on) return;
    setFloat(program, "u_contactThickness", frame.lsLength(wsThickness));
    setFloat(program, "u_contactDistance", frame.lsLength(wsDistance));
    setInt(program, "u_contactPosition", kPositionUnit);
    setInt(program, "u_contactNormal", kNormalUnit);
}

void ContactShadows::bindCameraImages(const CameraPass& camera) const {
    if (!on) return;
    glBindTextureUnit(kPositionUnit, camera.positionTexture());
    glBindTextureUnit(kNormalUnit, camera.normalTexture());
}

}  // namespace so
