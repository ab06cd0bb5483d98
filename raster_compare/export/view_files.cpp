#include "raster_compare/export/view_files.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "core/camera.h"
#include "core/error.h"
#include "core/image.h"
#include "core/scene_writer.h"
#include "core/tool_info.h"
#include "oracle/primary_image.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json vec3Json(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

// 16 numbers, column-major: element (row r, column c) at index 4c + r, as glm::value_ptr.
json matrixJson(const glm::dmat4& m) {
    json a = json::array();
    const double* p = glm::value_ptr(m);
    for (int i = 0; i < 16; ++i) a.push_back(p[i]);
    return a;
}

// Vulkan's clip space from OpenGL's: y down, depth z' = (z + w) / 2 in [0, w].
glm::dmat4 vulkanFromGl() {
    glm::dmat4 m(1.0);
    m[1][1] = -1.0;
    m[2][2] = 0.5;
    m[3][2] = 0.5;
    return m;
}

json cameraJson(const CameraDesc& desc, const Camera& camera, const Bounds3d& wsBounds) {
    double near = 0.0, far = 0.0;
    viewDepthRange(camera, wsBounds, near, far);
    const glm::dmat4 view = camera.viewFromWorld();
    const glm::dmat4 projGl = camera.clipFromView(near, far);
    return {{"eye", vec3Json(desc.wsEye)},
            {"target", vec3Json(desc.wsTarget)},
            {"up", vec3Json(desc.wsUp)},
            {"vfov_deg", desc.vfovDeg},
            {"width", camera.width()},
            {"height", camera.height()},
            {"pixel_center",
             "pixel (i, j) is sampled at (i + 0.5, j + 0.5) from the image's top-left corner; "
             "row 0 is the top row"},
            {"near", near},
            {"far", far},
            {"view_gl", matrixJson(view)},
            {"proj_gl", matrixJson(projGl)},
            {"view_vk", matrixJson(view)},
            {"proj_vk", matrixJson(vulkanFromGl() * projGl)}};
}

// The light's keys as the scene format names them (docs/scene-format.md), values as loaded.
json lightJson(const Light& l, const Bounds3d& wsBounds, const Bounds3d& lsReceivers) {
    json j = sceneLightJson(l);
    json faces = json::array();
    for (const LightSpaceFace& f : lightSpaceFaces(l, wsBounds, &lsReceivers))
        faces.push_back({{"face", f.face},
                         {"view", matrixJson(f.viewFromWorld)},
                         {"proj", matrixJson(f.clipFromView)}});
    j["light_space"] = faces;
    return j;
}

json sceneJson(const std::string& scenePath, const Scene& scene) {
    json geometry = json::array();
    for (const GeometrySource& g : scene.geometry)
        geometry.push_back({{"file", g.file.string()},
                            {"translate", vec3Json(g.translate)},
                            {"scale", vec3Json(g.scale)}});
    json bounds = nullptr;
    if (!scene.wsBounds.empty())
        bounds = {{"min", vec3Json(scene.wsBounds.lo)}, {"max", vec3Json(scene.wsBounds.hi)}};
    return {{"file", scenePath},
            {"hash", scene.contentHash},
            {"effects", scene.effects},
            {"bounds", bounds},
            {"geometry", geometry}};
}

}  // namespace

void viewDepthRange(const Camera& camera, const Bounds3d& wsBounds, double& near, double& far) {
    const glm::dvec3 eye = camera.wsEye();
    if (wsBounds.empty()) {
        near = 0.01, far = 100.0;
        return;
    }
    double farthest = 0.0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner((k & 1) ? wsBounds.hi.x : wsBounds.lo.x,
                                (k & 2) ? wsBounds.hi.y : wsBounds.lo.y,
                                (k & 4) ? wsBounds.hi.z : wsBounds.lo.z);
        farthest = std::max(farthest, glm::length(corner - eye));
    }
    far = std::max(1.01 * farthest, 1e-30);
    const double toBox = glm::length(glm::clamp(eye, wsBounds.lo, wsBounds.hi) - eye);
    near = std::max(0.99 * toBox, far * 1e-5);
}

void writeFileBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    if (out) out.write(bytes.data(), std::streamsize(bytes.size()));
    if (out) out.close();
    if (!out)
        throwInputError(path.string(), "",
                        std::string("cannot be written (") + std::strerror(errno) + ")");
}

ViewFiles writeViewFiles(const Scene& scene, const std::string& scenePath,
                         const OracleOptions& oracle, const fs::path& outDir) {
    const CameraDesc desc = effectiveCamera(scene, oracle);
    const Camera camera(desc);
    const PrimaryImage primary = tracePrimaryImage(scene, oracle);
    json lights = json::array();
    for (const Light& l : scene.lights)
        lights.push_back(lightJson(l, scene.wsBounds, primary.lsReceivers));
    const json view = {{"view_format", kViewFormat},
                       {"tool", toolJson()},
                       {"scene", sceneJson(scenePath, scene)},
                       {"camera", cameraJson(desc, camera, scene.wsBounds)},
                       {"lights", lights}};
    ViewFiles files{outDir / "view.json", outDir / "gbuffer.exr"};
    writeExr(files.gbufferExr.string(), primary.image,
             {{"shadowOracle/sceneHash", scene.contentHash}});
    writeFileBytes(files.viewJson, view.dump(2) + "\n");
    return files;
}

}  // namespace so
