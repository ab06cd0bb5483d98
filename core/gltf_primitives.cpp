#include "core/gltf_primitives.h"

#include <cmath>
#include <cstring>
#include <string>

namespace so::gltf_detail {
namespace {

std::string primField(size_t mesh, size_t prim) {
    return idx("meshes", mesh) + "." + idx("primitives", prim);
}

uint32_t readIndex(const AccessorData& a, uint64_t i) {
    const unsigned char* p = a.base + i * a.stride;
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return p[0];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        default: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
    }
}

// POSITION: VEC3 FLOAT, or with KHR_mesh_quantization VEC3 of (normalized or not) BYTE,
// UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT (the extension's table; the node transform scales them).
void checkPositionType(const Context& ctx, const tinygltf::Accessor& a, size_t index) {
    const bool quantizedType = a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                               a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                               a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
                               a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (a.type == TINYGLTF_TYPE_VEC3 && a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
    if (a.type == TINYGLTF_TYPE_VEC3 && quantizedType && ctx.meshQuantization) return;
    fail(ctx, idx("accessors", index),
         a.type == TINYGLTF_TYPE_VEC3 && quantizedType
             ? "POSITION must be VEC3 FLOAT (integer positions need KHR_mesh_quantization in "
               "extensionsUsed)"
             : "POSITION must be VEC3 FLOAT, or with KHR_mesh_quantization VEC3 BYTE, "
               "UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT");
}

void checkIndexType(const Context& ctx, const tinygltf::Accessor& a, int index,
                    const std::string& field) {
    if (a.type != TINYGLTF_TYPE_SCALAR ||
        (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        fail(ctx, field + ".indices",
             idx("accessors", size_t(index)) +
                 " must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
}

// The triangles a primitive's elements make in its mode (a TRIANGLES count must be a multiple
// of 3).
uint64_t plannedTriangles(const Context& ctx, const PlannedPrimitive& pp,
                          const std::string& field) {
    if (pp.mode != TINYGLTF_MODE_TRIANGLES) return pp.elements < 3 ? 0 : pp.elements - 2;
    if (pp.elements % 3 != 0)
        fail(ctx, field + (pp.indices ? ".indices" : ".attributes.POSITION"),
             "TRIANGLES with " + std::to_string(pp.elements) + " elements, not a multiple of 3");
    return pp.elements / 3;
}

}  // namespace

std::optional<PlannedPrimitive> planPrimitive(const Context& ctx, const tinygltf::Model& model,
                                              const Json& doc, const Instance& inst, size_t k,
                                              PlanCounts& counts) {
    const size_t meshIndex = size_t(model.nodes[inst.node].mesh);
    const tinygltf::Primitive& prim = model.meshes[meshIndex].primitives[k];
    const std::string field = primField(meshIndex, k);
    counts.skinsOrMorphs |= !prim.targets.empty();
    if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
        fail(ctx, field + ".mode", "invalid mode " + std::to_string(prim.mode));
    if (prim.mode < TINYGLTF_MODE_TRIANGLES) {
        ++counts.nonTriangle;
        return std::nullopt;
    }
    PlannedPrimitive pp{inst, meshIndex, k, {}, std::nullopt, prim.mode, 0, 0, nullptr};
    auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) fail(ctx, field + ".attributes", "no POSITION");
    pp.positions = checkedAccessor(
        ctx, model, doc, pos->second, field + ".attributes.POSITION",
        [&](const tinygltf::Accessor& a) { checkPositionType(ctx, a, size_t(pos->second)); });
    if (pp.positions.count > 3 * ctx.limits.maxTrianglesPerMesh)
        fail(ctx, idx("accessors", size_t(pos->second)) + ".count",
             std::to_string(pp.positions.count) + " vertices, over 3 x maxTrianglesPerMesh");
    pp.elements = pp.positions.count;
    if (prim.indices >= 0) {
        pp.indices = checkedAccessor(
            ctx, model, doc, prim.indices, field + ".indices",
            [&](const tinygltf::Accessor& a) { checkIndexType(ctx, a, prim.indices, field); });
        pp.elements = pp.indices->count;
    }
    pp.triangles = plannedTriangles(ctx, pp, field);
    if (pp.triangles == 0) {
        ++counts.empty;
        return std::nullopt;
    }
    if (pp.triangles > ctx.limits.maxTrianglesPerMesh)
        fail(ctx, field,
             std::to_string(pp.triangles) + " triangles, over the limit of " +
                 std::to_string(ctx.limits.maxTrianglesPerMesh));
    return pp;
}

void addToPlan(const Context& ctx, const PlannedPrimitive& pp, std::vector<PlannedPrimitive>& plan,
               PlanCounts& counts) {
    if (plan.size() + 1 > ctx.limits.maxMeshes)
        fail(ctx, "meshes",
             "more than " + std::to_string(ctx.limits.maxMeshes) + " drawn primitives");
    counts.totalTriangles += pp.triangles;
    counts.totalVertices += pp.positions.count;
    if (counts.totalTriangles > ctx.limits.maxTotalTriangles)
        fail(ctx, "meshes",
             "more than " + std::to_string(ctx.limits.maxTotalTriangles) + " triangles in all");
    if (counts.totalVertices > 3 * ctx.limits.maxTotalTriangles)
        fail(ctx, "meshes",
             "more than " + std::to_string(3 * ctx.limits.maxTotalTriangles) + " vertices in all");
    plan.push_back(pp);
}

void planWarnings(const PlanCounts& counts, GltfContent& out) {
    if (counts.nonTriangle > 0)
        out.warnings.push_back(std::to_string(counts.nonTriangle) +
                               " point or line primitive(s) skipped (only triangles are traced)");
    if (counts.empty > 0)
        out.warnings.push_back(std::to_string(counts.empty) +
                               " primitive(s) with no triangle skipped");
    if (counts.skinsOrMorphs)
        out.warnings.push_back("skins and morph targets are ignored (meshes drawn in rest pose)");
    out.skippedPrimitives = counts.nonTriangle + counts.empty;
}

MeshPrimitive buildPrimitive(const Context& ctx, const tinygltf::Model& model, const Json& doc,
                             const PlannedPrimitive& pp, GltfAlpha& alpha) {
    const Instance& inst = pp.instance;
    const tinygltf::Node& node = model.nodes[inst.node];
    const tinygltf::Mesh& mesh = model.meshes[pp.mesh];
    const tinygltf::Primitive& prim = mesh.primitives[pp.prim];
    std::string field = primField(pp.mesh, pp.prim);
    MeshPrimitive out;
    out.name = ctx.displayName + "#" +
               (node.name.empty() ? "node" + std::to_string(inst.node) : printable(node.name)) +
               "/" + (mesh.name.empty() ? "mesh" + std::to_string(pp.mesh) : printable(mesh.name)) +
               "/prim" + std::to_string(pp.prim);

    const std::string posField = idx("accessors", size_t(prim.attributes.at("POSITION")));
    out.wsPositions.resize(size_t(pp.positions.count));
    for (uint64_t i = 0; i < pp.positions.count; ++i) {
        float f[3];
        for (int c = 0; c < 3; ++c) f[c] = readComponent(pp.positions, i, c);
        if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2]))
            fail(ctx, posField, "POSITION " + std::to_string(i) + " is not finite");
        glm::dvec3 p = glm::dvec3(inst.world * glm::dvec4(f[0], f[1], f[2], 1.0));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            fail(ctx, idx("nodes", inst.node),
                 "world position of " + field + " vertex " + std::to_string(i) + " is not finite");
        out.wsPositions[size_t(i)] = p;
    }
    if (pp.animation) {
        auto animation = std::make_shared<MeshAnimation>(*pp.animation);
        animation->lsPositions.resize(size_t(pp.positions.count));
        for (uint64_t i = 0; i < pp.positions.count; ++i)
            for (int c = 0; c < 3; ++c)
                animation->lsPositions[size_t(i)][c] = readComponent(pp.positions, i, c);
        out.animation = std::move(animation);
    }

    std::vector<uint32_t> elements(size_t(pp.elements));
    for (uint64_t i = 0; i < pp.elements; ++i) {
        uint32_t v = pp.indices ? readIndex(*pp.indices, i) : uint32_t(i);
        if (v >= pp.positions.count)
            fail(ctx, field + ".indices",
                 "index " + std::to_string(v) + " (element " + std::to_string(i) +
                     ") >= vertex count " + std::to_string(pp.positions.count));
        elements[size_t(i)] = v;
    }
    if (pp.mode == TINYGLTF_MODE_TRIANGLES) {
        out.indices = std::move(elements);
    } else {
        out.indices.reserve(size_t(pp.triangles) * 3);
        for (size_t i = 0; i < size_t(pp.triangles); ++i) {
            if (pp.mode == TINYGLTF_MODE_TRIANGLE_FAN)
                out.indices.insert(out.indices.end(),
                                   {elements[0], elements[i + 1], elements[i + 2]});
            else if (i % 2 == 0)
                out.indices.insert(out.indices.end(),
                                   {elements[i], elements[i + 1], elements[i + 2]});
            else
                out.indices.insert(out.indices.end(),
                                   {elements[i + 1], elements[i], elements[i + 2]});
        }
    }
    alpha.apply(prim, pp.positions.count, field, out);
    if (prim.material >= 0 && size_t(prim.material) < model.materials.size())
        out.doubleSided = model.materials[size_t(prim.material)].doubleSided;
    // A lightmap's coordinates, when the file has them
    // (raster_compare/gl/lightmaps/lightmap_atlas.h).
    if (auto uv1 = prim.attributes.find("TEXCOORD_1"); uv1 != prim.attributes.end())
        out.lightmapUvs = readTexCoords(ctx, model, doc, uv1->second, "TEXCOORD_1",
                                        pp.positions.count, field, glm::dmat3(1.0));
    return out;
}

}  // namespace so::gltf_detail
