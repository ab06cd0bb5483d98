#include "oracle/accel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "core/alpha_mask.h"
#include "core/error.h"

namespace so {

namespace {

using AlphaGeometry = Accel::AlphaGeometry;

thread_local uint64_t tAlphaTests = 0;

// Rejects a candidate hit on the triangle the ray leaves from: the ray's id holds the origin
// triangle's global index, the context the meshes' first global indices. A context filter, run by
// the queries whose ShadowContext turned it on. Like every filter, called from Embree's C code
// during a query: noexcept (nothing here may throw, and no SO_CHECK belongs here), so that a slip
// ends in std::terminate rather than undefined behaviour.
void skipOriginTriangle(const RTCFilterFunctionNArguments* args) noexcept {
    const auto* ctx = reinterpret_cast<const ShadowContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const unsigned origin = RTCRayN_id(args->ray, args->N, i);
        const unsigned mesh = RTCHitN_geomID(args->hit, args->N, i);
        const unsigned hit = ctx->meshBase[mesh] + RTCHitN_primID(args->hit, args->N, i);
        if (origin == hit) args->valid[i] = 0;
    }
}

// Alpha-tested geometry: the origin triangle is skipped as above (where asked), and a candidate
// hit where the material's alpha is below its cutoff is no hit (core/alpha_mask.h), for every ray:
// primary, shadow, closest or any hit. The texture coordinate is interpolated with Embree's
// barycentrics, as the raster path interpolates it across the triangle.
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

// The index buffer Embree gets. A triangle of zero area in double (local frame) becomes (i, i, i),
// zero area in float too, so Embree never hits it: the three roundings to float are independent,
// and a triangle degenerate in double (say, one vertex the exact midpoint of the others) can be a
// sliver in float that Embree hits, where the primary pass's double normal would be 0 / 0 = NaN
// (docs/hard-cases.md: 4 pixels of 65,536 over 20,000 such triangles). The triangle keeps its
// index, so id.prim stays that of the index buffer.
void copyIndicesWithoutDegenerates(const std::vector<glm::dvec3>& ls,
                                   const std::vector<uint32_t>& indices, uint32_t* ib) {
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::dvec3 &a = ls[indices[t]], &b = ls[indices[t + 1]], &c = ls[indices[t + 2]];
        const bool degenerate = glm::cross(b - a, c - a) == glm::dvec3(0.0);
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

}  // namespace

Accel::Accel(const Scene& scene, const EmbreeDevice& device, bool originFilter)
    : frame_(LocalFrame::fit(scene.wsBounds)), rtcScene_(device), filters_(originFilter) {
    RTCScene s = rtcScene_.get();
    // Robust: watertight along shared edges, which is what a ground truth needs (contact lines,
    // closed meshes). High build quality: built once, traced many times. The origin filter is a
    // context filter, run only by the queries that ask for it.
    rtcSetSceneFlags(s, originFilter
                            ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION
                            : RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    meshes_.reserve(scene.meshes.size());
    uint64_t base = 0;
    for (size_t id = 0; id < scene.meshes.size(); ++id) {
        const MeshPrimitive& mesh = scene.meshes[id];
        // The loader caps the total at 2^28 triangles: the global index fits a ray id. A scene
        // built by a caller may not have been through the loader.
        if (base + mesh.triangleCount() >= uint64_t(kNoOriginTriangle))
            throw std::invalid_argument("scene: more than 2^32 - 2 triangles");
        meshBase_.push_back(unsigned(base));
        alphaByMesh_.push_back(nullptr);
        MeshData data{{}, mesh.wsPositions, mesh.indices};
        data.lsPositions.reserve(mesh.wsPositions.size());
        for (const glm::dvec3& ws : mesh.wsPositions)
            data.lsPositions.push_back(frame_.lsFromWs(ws));
        checkFinite(data.lsPositions, id);

        EmbreeGeometry g(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vb = static_cast<float*>(g.newBuffer(RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                   3 * sizeof(float), data.lsPositions.size()));
        for (size_t i = 0; i < data.lsPositions.size(); ++i)
            for (int k = 0; k < 3; ++k) vb[3 * i + k] = float(data.lsPositions[i][k]);
        auto* ib = static_cast<uint32_t*>(g.newBuffer(RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                      3 * sizeof(uint32_t), mesh.triangleCount()));
        copyIndicesWithoutDegenerates(data.lsPositions, mesh.indices, ib);
        rtcSetGeometryMask(g.get(), 0xFFFFFFFFu);
        if (scene.alphaTested(id)) {
            auto a = std::make_unique<AlphaGeometry>();
            a->base = unsigned(base);
            a->skipOrigin = originFilter;
            a->mask = &*mesh.alpha;
            if (mesh.alpha->texture >= 0) {
                a->texture = &scene.alphaTextures[size_t(mesh.alpha->texture)];
                a->uvs = mesh.uvs.data();
                a->indices = mesh.indices.data();
                if (mesh.uvs.size() != mesh.wsPositions.size())
                    throw std::invalid_argument("scene: mesh " + std::to_string(id) + " has " +
                                                std::to_string(mesh.uvs.size()) + " uvs for " +
                                                std::to_string(mesh.wsPositions.size()) +
                                                " positions");
            }
            rtcSetGeometryUserData(g.get(), a.get());
            rtcSetGeometryOccludedFilterFunction(g.get(), alphaTestHit);
            rtcSetGeometryIntersectFilterFunction(g.get(), alphaTestHit);
            alphaByMesh_.back() = a.get();
            alphaGeometries_.push_back(std::move(a));
        }
        g.commit();
        rtcScene_.attach(g, unsigned(id));  // the scene keeps its own reference to g
        meshes_.push_back(std::move(data));
        base += mesh.triangleCount();
    }
    rtcScene_.commit();
}

void ShadowContext::originFilter(bool on) {
    rtc.filter = on ? skipOriginTriangle : nullptr;
}

ShadowContext Accel::shadowContext(bool coherent) const {
    ShadowContext c;
    rtcInitIntersectContext(&c.rtc);
    if (coherent) c.rtc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    c.meshBase = meshBase_.data();
    return c;
}

RTCRayHit singleRayHit(const glm::vec3& org, const glm::vec3& dir, float tfar) {
    RTCRayHit rh;
    rh.ray.org_x = org.x;
    rh.ray.org_y = org.y;
    rh.ray.org_z = org.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xFFFFFFFFu;  // a zero mask would hit nothing (Embree masks are on)
    rh.ray.time = 0.0f;
    rh.ray.flags = 0;
    rh.ray.id = kNoOriginTriangle;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

uint64_t Accel::alphaTestsOnThisThread() {
    return tAlphaTests;
}

}  // namespace so
