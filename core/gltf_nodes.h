// A glTF file's node hierarchy: each node's local transform, the graph checked (indices in range,
// no cycle), and its depth-first traversal from the scene's roots into node instances with their
// world transforms (docs/scene-format.md; the order is gltf_loader.cpp's public contract).
// Internal to the glTF loader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/gltf_detail.h"

namespace so::gltf_detail {

// One visit of a node: a node reached along several paths (instancing) has one instance a path.
struct Instance {
    size_t node;
    glm::dmat4 world;
    int64_t link = -1;  // into the ChainLink list, when animations play
};

// The path from a root down to one node instance, one link a visit (a node reached along several
// paths has several), kept only when animations play: a moving primitive's chain is read from it.
struct ChainLink {
    size_t node;
    int64_t parent;  // -1 at a root
    bool moving;     // this node or an ancestor on the path is animated
};

// `matrix` if given (affine), else T * R * S with the quaternion normalised; every number finite.
glm::dmat4 localTransform(const Context& ctx, const tinygltf::Node& n, size_t i);
// Every node's mesh and camera index in range, before the graph is walked.
void checkNodeIndices(const Context& ctx, const tinygltf::Model& model);
// Rejects out-of-range children and cycles anywhere in the node graph, iteratively (a hostile file
// must not exhaust the stack).
void checkNodeGraph(const Context& ctx, const tinygltf::Model& model);

// Calls visit(Instance) in traversal order (depth-first, pre-order, children in the order listed)
// from the scene's roots, each world transform being wsFromFile * parent chain * local. Instances
// are not stored: only what they produce is. `links`, when not null, gets one ChainLink a visit.
// Run after checkNodeIndices and checkNodeGraph.
void traverse(const Context& ctx, const tinygltf::Model& model, const Json& doc,
              const glm::dmat4& wsFromFile, std::vector<ChainLink>* links,
              const std::function<void(const Instance&)>& visit);

// The unit vector `m` takes the direction `local` to; fails naming `field` if it collapses.
glm::dvec3 unitDirection(const Context& ctx, const glm::dmat4& m, const glm::dvec3& local,
                         const std::string& field);

}  // namespace so::gltf_detail
