// KHR_lights_punctual: the lights array checked on the raw JSON before tinygltf reads it, and one
// scene Light per visit of a node that has a light, named after it and made unique ("_2", "_3"...).
// Internal to the glTF loader (gltf_loader.cpp).
#pragma once

#include <set>
#include <string>

#include "core/gltf_detail.h"
#include "core/gltf_nodes.h"

namespace so::gltf_detail {

// tinygltf fails the whole load on a bad light with a message that names no light.
void checkLights(const Context& ctx, const Json& doc);
// Appends the instance's light, if its node has one, to ctx.out->lights; `names` holds the names
// given so far.
void addLight(const Context& ctx, const tinygltf::Model& model, const Instance& inst,
              std::set<std::string>& names);

}  // namespace so::gltf_detail
