// The glTF camera a scene takes: the first node instance, in traversal order, with a camera
// (docs/scene-format.md). Internal to the glTF loader (gltf_loader.cpp).
#pragma once

#include <optional>

#include "core/gltf_detail.h"
#include "core/gltf_nodes.h"

namespace so::gltf_detail {

// Sets `camera` from the instance's node if it is the first with a camera (`cameraSeen` says one
// was met); an orthographic camera is ignored with a warning, leaving no camera.
void addCamera(const Context& ctx, const tinygltf::Model& model, const Instance& inst,
               std::optional<CameraDesc>& camera, bool& cameraSeen);

}  // namespace so::gltf_detail
