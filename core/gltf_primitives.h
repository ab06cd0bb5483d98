// A glTF file's mesh primitives, in two passes: each one met in traversal order is checked and
// planned (its accessors, its mode, its triangle count, the scene's limits) before anything is
// allocated, then each planned one is built into a MeshPrimitive (world-space positions,
// triangle-list indices, alpha mask, lightmap coordinates). Internal to the glTF loader
// (gltf_loader.cpp, whose header states the naming and the strip and fan rules).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/gltf_alpha.h"
#include "core/gltf_detail.h"
#include "core/gltf_nodes.h"
#include "core/scene.h"

namespace so::gltf_detail {

// One primitive to draw: where its data lies, checked, and what it makes.
struct PlannedPrimitive {
    Instance instance;
    size_t mesh, prim;
    AccessorData positions;
    std::optional<AccessorData> indices;
    int mode;
    uint64_t elements;  // index count, or vertex count when not indexed
    uint64_t triangles;
    std::shared_ptr<MeshAnimation> animation;  // a moving primitive's chain (no positions yet)
};

// What the first pass counts besides the plan: the primitives it skips, the totals the limits
// bound, and whether anything animates (ignored, with a warning).
struct PlanCounts {
    size_t nonTriangle = 0, empty = 0;
    uint64_t totalTriangles = 0, totalVertices = 0;
    bool skinsOrMorphs = false;
};

// Primitive k of the instance's mesh, checked and counted: its plan, or nothing for a point, line
// or empty primitive (counted in `counts`).
std::optional<PlannedPrimitive> planPrimitive(const Context& ctx, const tinygltf::Model& model,
                                              const Json& doc, const Instance& inst, size_t k,
                                              PlanCounts& counts);
// The limits on the whole scene, checked as each primitive joins the plan, so that nothing is
// allocated past them.
void addToPlan(const Context& ctx, const PlannedPrimitive& pp, std::vector<PlannedPrimitive>& plan,
               PlanCounts& counts);
// The warnings for what the plan skipped or ignores, and out.skippedPrimitives.
void planWarnings(const PlanCounts& counts, GltfContent& out);

// The MeshPrimitive of a planned primitive; `alpha` gives it its mask if its material has one.
MeshPrimitive buildPrimitive(const Context& ctx, const tinygltf::Model& model, const Json& doc,
                             const PlannedPrimitive& pp, GltfAlpha& alpha);

}  // namespace so::gltf_detail
