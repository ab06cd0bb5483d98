// Reading a glTF file's animations (spec 3.11) into core/gltf_animation.h's tracks, for the loader
// (gltf_loader.cpp) of a scene with a `sequence`. Every accessor a played channel reads is checked
// like the loader's others; internal to core/.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/gltf_animation.h"
#include "core/gltf_detail.h"
#include "core/gltf_nodes.h"

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

// The chain of a node instance under a moving node: every node from its root down, the still
// ones (made once, in `still`) at their own local transform. A skinned mesh there is refused:
// rigid motion would move its bind pose, not what its author animated.
std::shared_ptr<MeshAnimation> meshAnimation(
    const Context& ctx, const tinygltf::Model& model, const std::vector<ChainLink>& links,
    const Instance& inst, const glm::dmat4& wsFromFile,
    std::vector<std::shared_ptr<const AnimatedNode>>& still);

// A scene with a sequence: the played clips' nodes (into ctx.animatedNodes), and whether the clip
// named is in the file (with the file's clip names, into ctx.out). Nothing without a sequence.
void readAnimations(Context& ctx, const tinygltf::Model& model, const Json& doc);

}  // namespace so::gltf_detail
