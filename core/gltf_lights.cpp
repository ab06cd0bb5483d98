#include "core/gltf_lights.h"

#include <cmath>
#include <numbers>

#include "core/channels.h"
#include "core/lights/make_light.h"

namespace so::gltf_detail {

void checkLights(const Context& ctx, const Json& doc) {
    const Json* ext = member(doc, "extensions");
    const Json* khr = ext ? member(*ext, "KHR_lights_punctual") : nullptr;
    const Json* lights = khr ? member(*khr, "lights") : nullptr;
    if (!lights) return;
    if (!lights->is_array()) fail(ctx, "KHR_lights_punctual.lights", "not an array");
    for (size_t i = 0; i < lights->size(); ++i) {
        std::string field = "KHR_lights_punctual." + idx("lights", i);
        const Json& l = (*lights)[i];
        const Json* type = member(l, "type");
        if (!type || !type->is_string()) fail(ctx, field + ".type", "missing or not a string");
        const std::string& t = type->get_ref<const std::string&>();
        if (t != "point" && t != "directional" && t != "spot")
            fail(ctx, field + ".type", "unknown light type " + quoted(t));
        if (t == "spot" && !(member(l, "spot") && member(l, "spot")->is_object()))
            fail(ctx, field + ".spot", "a spot light needs a 'spot' object");
    }
}

void addLight(const Context& ctx, const tinygltf::Model& model, const Instance& inst,
              std::set<std::string>& names) {
    const tinygltf::Node& node = model.nodes[inst.node];
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return;
    std::string field = idx("nodes", inst.node) + ".extensions.KHR_lights_punctual.light";
    const tinygltf::Value& v = ext->second.Get("light");
    if (!v.IsInt()) fail(ctx, field, "missing or not an integer");
    int li = v.Get<int>();
    if (li < 0 || size_t(li) >= model.lights.size())
        fail(ctx, field,
             "light " + std::to_string(li) + " out of range (" +
                 std::to_string(model.lights.size()) + " lights)");
    if (ctx.out->lights.size() >= ctx.limits.maxLights)
        fail(ctx, "KHR_lights_punctual",
             "more than " + std::to_string(ctx.limits.maxLights) + " lights in the scene");
    const tinygltf::Light& src = model.lights[size_t(li)];
    std::string lightField = "KHR_lights_punctual." + idx("lights", size_t(li));
    const glm::dvec3 wsAt(inst.world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    Light l = pointLight("", wsAt);
    if (src.type != "point") {
        // Normalising drops the node's (uniform) scale, which glTF says lights ignore.
        const glm::dvec3 wsAlong =
            unitDirection(ctx, inst.world, {0.0, 0.0, -1.0}, idx("nodes", inst.node));
        if (src.type == "spot") {
            double inner = src.spot.innerConeAngle * 180.0 / std::numbers::pi;
            double outer = src.spot.outerConeAngle * 180.0 / std::numbers::pi;
            if (!(inner >= 0.0 && inner <= outer && outer > 0.0 && outer <= 90.0))
                fail(ctx, lightField + ".spot",
                     "need 0 <= innerConeAngle <= outerConeAngle <= pi/2 and outerConeAngle > 0");
            l = spotLight("", wsAt, wsAlong, outer, inner);
        } else {
            l = directionalLight("", wsAlong);
            l.wsPosition =
                wsAt;  // the node's place, kept as before (a directional light ignores it)
        }
    }
    std::string base = channels::sanitizeLayerName(src.name, "light" + std::to_string(li));
    std::string name = base;
    for (size_t n = 2; names.count(name); ++n) {
        std::string suffix = "_" + std::to_string(n);
        name = base.substr(0, 64 - suffix.size()) + suffix;
    }
    SO_CHECK(channels::isValidLayerName(name));
    names.insert(name);
    l.name = name;
    ctx.out->lights.push_back(std::move(l));
}

}  // namespace so::gltf_detail
