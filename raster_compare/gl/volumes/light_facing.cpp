#include "raster_compare/gl/volumes/light_facing.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {

GlProgram buildLightFacingProgram(const Light& light, const GpuScene& scene,
                                  const CameraPass& camera) {
    const std::string defines = lightCameraDefines(light);
    GlProgram p = buildProgram(scene.alphaDefines() + defines, shaders::scene_vert,
                               {shaders::alpha_test_glsl, shaders::light_facing_frag});
    const GLuint id = p.get();
    setMat4(id, "u_clipFromLocal", camera.clipFromLocal());
    setVec3(id, "u_lsEye", camera.lsEye());
    setVec3(id, "u_lsLightPosition", scene.frame().lsFromWs(light.wsPosition));
    setVec3(id, "u_lsLightDirection", glm::normalize(light.wsDirection));
    setVec3(id, "u_lsEmitNormal", light.wsEmitNormal());  // the local frame only scales, moves
    setFloat(id, "u_cosOuter", std::cos(light.outerConeDeg * 3.14159265358979323846 / 180.0));
    return p;
}

}  // namespace so
