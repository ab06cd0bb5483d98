#include "embree/triangle_scene.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/alpha_mask.h"

namespace so {

namespace {

thread_local uint64_t tAlphaTests = 0;

// Alpha-tested geometry: the origin triangle is skipped (where asked), and a candidate hit where
// the material's alpha is below its cutoff is no hit (core/alpha_mask.h), for every ray: primary,
// shadow, closest or any hit. Called from Embree's C code during a query: noexcept (nothing here
// may throw, and no SO_CHECK belongs here), so that a slip ends in std::terminate rather than
// undefined behaviour.
void alphaTestHit(const RTCFilterFunctionNArguments* args) noexcept {
    const auto* a = static_cast<const AlphaGeometry*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        if (a->skipOrigin && RTCRayN_id(args->ray, args->N, i) == a->base + prim) {
            args->valid[i] = 0;
            continue;
        }
        ++tAlphaTests;
        glm::vec2 uv(0.0f);
        if (a->texture) {
            const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
            const uint32_t* t = &a->indices[3 * size_t(prim)];
            uv = (1.0f - u - v) * a->uvs[t[0]] + u * a->uvs[t[1]] + v * a->uvs[t[2]];
        }
        if (!alphaKeeps(*a->mask, a->texture, uv)) args->valid[i] = 0;
    }
}

// The index buffer Embree gets, degenerate triangles dropped where asked
// (TriangleSceneOptions::dropDegenerates).
void copyIndices(const std::vector<glm::dvec3>& ls, const std::vector<uint32_t>& indices,
                 bool dropDegenerates, uint32_t* ib) {
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::dvec3 &a = ls[indices[t]], &b = ls[indices[t + 1]], &c = ls[indices[t + 2]];
        const bool degenerate = dropDegenerates && glm::cross(b - a, c - a) == glm::dvec3(0.0);
        for (size_t k = 0; k < 3; ++k) ib[t + k] = degenerate ? indices[t] : indices[t + k];
    }
}

// The loader rejects non-finite input and the frame keeps |ls| near 1, so this only fires for a
// scene built without the loader (or on a bug); Embree would otherwise drop the triangle silently.
void checkFinite(const std::vector<glm::dvec3>& lsPositions, size_t mesh) {
    for (const glm::dvec3& p : lsPositions)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(float(p[k])))
                throw std::invalid_argument("scene: mesh " + std::to_string(mesh) +
                                            " has a vertex position that is not finite");
}

// The filter's data for alpha-tested mesh `id`, whose first triangle has global index `base`.
std::unique_ptr<AlphaGeometry> alphaGeometryOf(const Scene& scene, size_t id, unsigned base,
                                               bool skipOrigin) {
    const MeshPrimitive& mesh = scene.meshes[id];
    auto a = std::make_unique<AlphaGeometry>();
    a->base = base;
    a->skipOrigin = skipOrigin;
    a->mask = &*mesh.alpha;
    if (mesh.alpha->texture >= 0) {
        a->texture = &scene.alphaTextures[size_t(mesh.alpha->texture)];
        a->uvs = mesh.uvs.data();
        a->indices = mesh.indices.data();
        if (mesh.uvs.size() != mesh.wsPositions.size())
            throw std::invalid_argument("scene: mesh " + std::to_string(id) + " has " +
                                        std::to_string(mesh.uvs.size()) + " uvs for " +
                                        std::to_string(mesh.wsPositions.size()) + " positions");
    }
    return a;
}

}  // namespace

TriangleScene::TriangleScene(const Scene& scene, const LocalFrame& frame,
                             const EmbreeDevice& device, const TriangleSceneOptions& options)
    : rtcScene_(device) {
    RTCScene s = rtcScene_.get();
    RTCSceneFlags flags = RTC_SCENE_FLAG_NONE;
    if (options.robust) flags = flags | RTC_SCENE_FLAG_ROBUST;
    if (options.contextFilter) flags = flags | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
    rtcSetSceneFlags(s, flags);
    rtcSetSceneBuildQuality(s, options.quality);
    device.throwIfError();
    meshes_.reserve(scene.meshes.size());
    uint64_t base = 0;
    for (size_t id = 0; id < scene.meshes.size(); ++id) {
        // The loader caps the total at 2^28 triangles: the global index fits a ray id. A scene
        // built by a caller may not have been through the loader.
        if (base + scene.meshes[id].triangleCount() >= uint64_t(kNoOriginTriangle))
            throw std::invalid_argument("scene: more than 2^32 - 2 triangles");
        meshBase_.push_back(unsigned(base));
        addMesh(scene, id, frame, device, options);
        base += scene.meshes[id].triangleCount();
    }
    rtcScene_.commit();
}

void TriangleScene::addMesh(const Scene& scene, size_t id, const LocalFrame& frame,
                            const EmbreeDevice& device, const TriangleSceneOptions& options) {
    const MeshPrimitive& mesh = scene.meshes[id];
    alphaByMesh_.push_back(nullptr);
    MeshData data{{}, mesh.wsPositions, mesh.indices};
    data.lsPositions.reserve(mesh.wsPositions.size());
    for (const glm::dvec3& ws : mesh.wsPositions) data.lsPositions.push_back(frame.lsFromWs(ws));
    checkFinite(data.lsPositions, id);

    EmbreeGeometry g(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(g.newBuffer(RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                               3 * sizeof(float), data.lsPositions.size()));
    for (size_t i = 0; i < data.lsPositions.size(); ++i)
        for (int k = 0; k < 3; ++k) vb[3 * i + k] = float(data.lsPositions[i][k]);
    auto* ib = static_cast<uint32_t*>(g.newBuffer(RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                  3 * sizeof(uint32_t), mesh.triangleCount()));
    copyIndices(data.lsPositions, mesh.indices, options.dropDegenerates, ib);
    rtcSetGeometryMask(g.get(), 0xFFFFFFFFu);
    if (scene.alphaTested(id)) {
        std::unique_ptr<AlphaGeometry> a =
            alphaGeometryOf(scene, id, meshBase_.back(), options.alphaSkipsOrigin);
        rtcSetGeometryUserData(g.get(), a.get());
        rtcSetGeometryOccludedFilterFunction(g.get(), alphaTestHit);
        rtcSetGeometryIntersectFilterFunction(g.get(), alphaTestHit);
        alphaByMesh_.back() = a.get();
        alphaGeometries_.push_back(std::move(a));
    }
    g.commit();
    rtcScene_.attach(g, unsigned(id));  // the scene keeps its own reference to g
    meshes_.push_back(std::move(data));
}

uint64_t TriangleScene::alphaTestsOnThisThread() {
    return tAlphaTests;
}

}  // namespace so
