#include "core/scene_writer.h"

#include <algorithm>

#include "core/lights/light_kind.h"

namespace so {

namespace {

using nlohmann::json;

json cameraPathJson(const CameraPath& path) {
    json keys = json::array();
    for (const CameraKeyframe& k : path.keyframes) {
        json key = {{"t", k.t}, {"eye", jsonVec3(k.wsEye)}, {"target", jsonVec3(k.wsTarget)}};
        if (k.wsUp) key["up"] = jsonVec3(*k.wsUp);
        if (k.vfovDeg) key["vfov_deg"] = *k.vfovDeg;
        keys.push_back(key);
    }
    return {{"keyframes", keys},
            {"interpolation",
             path.interpolation == PathInterpolation::CatmullRom ? "catmull-rom" : "linear"}};
}

}  // namespace

// The light as docs/scene-format.md spells it: only the keys its type takes.
json sceneLightJson(const Light& l) {
    json j = {{"name", l.name}, {"type", lightTypeName(l.type)}};
    lightKind(l.type).write(l, j);
    return j;
}

json sceneFileJson(const Scene& scene, const CameraDesc& camera, const std::string& geometryFile) {
    json lights = json::array();
    for (const Light& l : scene.lights) lights.push_back(sceneLightJson(l));
    // The oldest version that holds the scene, so older readers still load what they can.
    int format = 3;
    for (const Light& l : scene.lights) format = std::max(format, lightKind(l.type).sceneFormat());
    json j = {{"scene_format", format},
              {"geometry", json::array({{{"file", geometryFile}}})},
              {"camera",
               {{"eye", jsonVec3(camera.wsEye)},
                {"target", jsonVec3(camera.wsTarget)},
                {"up", jsonVec3(camera.wsUp)},
                {"vfov_deg", camera.vfovDeg},
                {"width", camera.width},
                {"height", camera.height}}},
              {"lights", lights},
              {"effects", scene.effects}};
    if (scene.cameraPath) j["camera_path"] = cameraPathJson(*scene.cameraPath);
    return j;
}

}  // namespace so
