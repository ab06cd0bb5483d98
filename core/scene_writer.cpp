#include "core/scene_writer.h"

namespace so {

namespace {

using nlohmann::json;

json vec3Json(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

json cameraPathJson(const CameraPath& path) {
    json keys = json::array();
    for (const CameraKeyframe& k : path.keyframes) {
        json key = {{"t", k.t}, {"eye", vec3Json(k.wsEye)}, {"target", vec3Json(k.wsTarget)}};
        if (k.wsUp) key["up"] = vec3Json(*k.wsUp);
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
    switch (l.type) {
        case LightType::Point:
            j["position"] = vec3Json(l.wsPosition);
            break;
        case LightType::Directional:
            j["direction"] = vec3Json(l.wsDirection);
            break;
        case LightType::Spot:
            j["position"] = vec3Json(l.wsPosition);
            j["direction"] = vec3Json(l.wsDirection);
            j["outer_cone_deg"] = l.outerConeDeg;
            j["inner_cone_deg"] = l.innerConeDeg;
            break;
        case LightType::Rect:
            j["center"] = vec3Json(l.wsPosition);
            j["u"] = vec3Json(l.wsU);
            j["v"] = vec3Json(l.wsV);
            break;
        case LightType::Disk:
            j["center"] = vec3Json(l.wsPosition);
            j["normal"] = vec3Json(l.wsNormal);
            j["radius"] = l.radius;
            break;
        case LightType::Sphere:
            j["center"] = vec3Json(l.wsPosition);
            j["radius"] = l.radius;
            break;
    }
    return j;
}

json sceneFileJson(const Scene& scene, const CameraDesc& camera, const std::string& geometryFile) {
    json lights = json::array();
    for (const Light& l : scene.lights) lights.push_back(sceneLightJson(l));
    json j = {{"scene_format", 3},
              {"geometry", json::array({{{"file", geometryFile}}})},
              {"camera",
               {{"eye", vec3Json(camera.wsEye)},
                {"target", vec3Json(camera.wsTarget)},
                {"up", vec3Json(camera.wsUp)},
                {"vfov_deg", camera.vfovDeg},
                {"width", camera.width},
                {"height", camera.height}}},
              {"lights", lights},
              {"effects", scene.effects}};
    if (scene.cameraPath) j["camera_path"] = cameraPathJson(*scene.cameraPath);
    return j;
}

}  // namespace so
