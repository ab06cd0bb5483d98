// Reading a glTF file's animations (spec 3.11) into core/gltf_animation.h's tracks, for the loader
// (gltf_loader.cpp) of a scene with a `sequence`. Every accessor a played channel reads is checked
// like the loader's others; internal to core/.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/gltf_animation.h"
#include "core/gltf_detail.h"

namespace so::gltf_detail {

// The nodes the played clips move, by node index (null for a node no played channel targets).
// `clip` names the clip that plays; empty: every clip. A file without that clip plays nothing
// (loadScene checks that some geometry file has it). Throws InputError for a played channel that
// targets `weights`, a node with a `matrix`, a property already animated, or reads a bad accessor.
std::vector<std::shared_ptr<const AnimatedNode>> playedAnimations(const Context& ctx,
                                                                  const tinygltf::Model& model,
                                                                  const Json& doc,
                                                                  const std::string& clip);

// The names of the file's animations ("animations[i]" for an unnamed one), for the error that
// lists them.
std::vector<std::string> animationNames(const tinygltf::Model& model);

}  // namespace so::gltf_detail
