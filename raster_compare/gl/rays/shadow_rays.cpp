#include "raster_compare/gl/rays/shadow_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/alpha_mask.h"
#include "core/lights/light_kind.h"
#include "core/sobol.h"
#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

// Embree reports errors through a callback that must not throw: it records the first, and the
// calls below throw after the Embree call that reported it.
void onEmbreeError(void* user, RTCError code, const char* text) {
    auto* first = static_cast<std::string*>(user);
    if (first->empty()) first->assign("Embree error " + std::to_string(int(code)) + ": " + text);
}

// An alpha-tested mesh's mask, for Embree's filter: a hit where the mask cuts the surface away is
// no hit, as for the oracle's rays (core/alpha_mask.h).
struct AlphaFilter {
    const MeshPrimitive* mesh = nullptr;
    const AlphaTexture* texture = nullptr;
};

void alphaFilter(const RTCFilterFunctionNArguments* args) {
    const auto* f = static_cast<const AlphaFilter*>(args->geometryUserPtr);
    for (unsigned k = 0; k < args->N; ++k) {
        if (args->valid[k] == 0) continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, k);
        const float u = RTCHitN_u(args->hit, args->N, k), v = RTCHitN_v(args->hit, args->N, k);
        const std::vector<glm::vec2>& uvs = f->mesh->uvs;
        glm::vec2 uv = glm::vec2(0.0f);
        if (!uvs.empty()) {
            const uint32_t* tri = &f->mesh->indices[3 * size_t(prim)];
            uv = (1.0f - u - v) * uvs[tri[0]] + u * uvs[tri[1]] + v * uvs[tri[2]];
        }
        if (!alphaKeeps(*f->mesh->alpha, f->texture, uv)) args->valid[k] = 0;
    }
}

// The light's sample k of the pixel's sequence, local frame; `lsEmitNormal` the emitter's normal
// there (zero for lights that are a point or a direction). A sphere's samples are uniform by area
// over the cap the point p sees (the same ratio estimate as over the whole sphere, whose other
// samples have G = 0: at one ray a pixel most pixels would otherwise get none).
struct LightSample {
    glm::dvec3 lsPoint{0.0}, lsEmitNormal{0.0};
};

// The offset of a ray's origin from the surface, in local units (the scene fits in [-1, 1]):
// above float rounding of the positions the camera pass interpolated.
constexpr double kOriginOffset = 2e-4;

}  // namespace

struct ShadowRayTracer::Impl {
    std::string error;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    LocalFrame frame;
    std::vector<AlphaFilter> filters;  // one per alpha-tested mesh: the filters' user data

    void throwIfError() {
        if (!error.empty()) throw std::runtime_error(error);
    }
};

ShadowRayTracer::ShadowRayTracer(const Scene& scene, const LocalFrame& frame)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.frame = frame;
    m.device = rtcNewDevice("threads=1");  // the BVH build; the rays use threads of their own
    if (!m.device) throw std::runtime_error("Embree could not make a device");
    // Set right after the device, so that no error is missed.
    rtcSetDeviceErrorFunction(m.device, onEmbreeError, &m.error);
    m.scene = rtcNewScene(m.device);
    size_t alphaTested = 0;
    for (size_t i = 0; i < scene.meshes.size(); ++i) alphaTested += scene.alphaTested(i) ? 1 : 0;
    m.filters.reserve(alphaTested);  // no reallocation: the geometries point into it
    for (size_t meshIndex = 0; meshIndex < scene.meshes.size(); ++meshIndex) {
        const MeshPrimitive& mesh = scene.meshes[meshIndex];
        if (mesh.indices.empty()) continue;
        RTCGeometry g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              mesh.wsPositions.size()));
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), mesh.indices.size() / 3));
        m.throwIfError();
        for (size_t i = 0; i < mesh.wsPositions.size(); ++i) {
            const glm::dvec3 ls = frame.lsFromWs(mesh.wsPositions[i]);
            v[3 * i] = float(ls.x), v[3 * i + 1] = float(ls.y), v[3 * i + 2] = float(ls.z);
        }
        std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
        if (scene.alphaTested(meshIndex)) {
            const int t = mesh.alpha->texture;
            m.filters.push_back({&mesh, t >= 0 ? &scene.alphaTextures[size_t(t)] : nullptr});
            rtcSetGeometryUserData(g, &m.filters.back());
            rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
            rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(m.scene, g);
        rtcReleaseGeometry(g);  // the scene keeps its own reference
    }
    rtcCommitScene(m.scene);
    m.throwIfError();
}

ShadowRayTracer::~ShadowRayTracer() {
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

namespace {

struct PixelTrace {
    float v = 0.0f, hit = 0.0f;
    uint32_t rays = 0;
};

// The light's sample for the pixel's own scrambled sequence at index `index`.
LightSample sampleLight(const Light& light, const LocalFrame& frame, const glm::dvec3& lsP,
                        uint32_t index, uint32_t seed) {
    LightSample s;
    const RasterAreaLightKind* area = rasterAreaLightKind(light.type);
    if (!area) {
        s.lsPoint = frame.lsFromWs(light.wsPosition);
        return s;
    }
    float u = 0.0f, v = 0.0f;
    sobol2D(index, seed, u, v);
    glm::dvec3 ws = area->samplePoint(light, double(u), double(v));
    if (!isOneSided(light)) {
        // cos(theta) from the axis towards p, uniform over the sphere, mapped affinely onto
        // [r / D, 1]: uniform by area over the cap that p sees (inside the sphere, none: the
        // oracle's V is 0 there, and so is G here).
        const glm::dvec3 toP = frame.wsFromLs(lsP) - light.wsPosition;
        const double D = glm::length(toP), r = light.radius;
        if (D > r && r > 0.0) {
            const glm::dvec3 axis = toP / D;
            const glm::dvec3 radial = (ws - light.wsPosition) / r;
            const double cosT = glm::dot(radial, axis);
            glm::dvec3 tangent = radial - cosT * axis;
            const double sinT = glm::length(tangent);
            tangent = sinT > 1e-12 ? tangent / sinT : glm::dvec3(0.0);
            const double k = r / D, cosCap = k + (1.0 - k) * std::abs(cosT);
            const double sinCap = std::sqrt(std::max(0.0, 1.0 - cosCap * cosCap));
            ws = light.wsPosition + r * (cosCap * axis + sinCap * tangent);
        }
    }
    s.lsPoint = frame.lsFromWs(ws);
    s.lsEmitNormal =
        isOneSided(light) ? light.wsEmitNormal() : glm::normalize(ws - light.wsPosition);
    return s;
}

// One pixel: spp rays from the offset point, V = sum(v G) / sum(G).
PixelTrace tracePixel(RTCScene scene, const Light& light, const LocalFrame& frame,
                      const glm::dvec3& lsP, const glm::dvec3& lsN, uint32_t pixelSeed,
                      const ShadowRaySettings& settings) {
    PixelTrace out;
    const bool directional = isDirectional(light);
    const bool area = rasterAreaLightKind(light.type) != nullptr;
    const glm::dvec3 origin = lsP + kOriginOffset * lsN;
    double sumG = 0.0, sumVG = 0.0, sumHit = 0.0;
    int hits = 0;
    for (int s = 0; s < settings.spp; ++s) {
        const LightSample ls = sampleLight(
            light, frame, lsP, uint32_t(settings.frameIndex) * uint32_t(settings.spp) + uint32_t(s),
            pixelSeed);
        glm::dvec3 d = directional ? -light.wsDirection : ls.lsPoint - origin;
        const double dist = directional ? std::numeric_limits<double>::infinity() : glm::length(d);
        if (!directional) d /= dist;
        const double cosR = glm::dot(lsN, d);
        double g = cosR > 0.0 ? 1.0 : 0.0;
        if (area) {
            const double cosE = -glm::dot(ls.lsEmitNormal, d);
            g = (cosR > 0.0 && cosE > 0.0) ? cosR * cosE / (dist * dist) : 0.0;
        } else if (hasCone(light)) {
            const double cosAxis = -glm::dot(d, light.wsDirection);
            if (cosAxis < std::cos(glm::radians(light.outerConeDeg))) g = 0.0;
        }
        if (g <= 0.0) continue;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        RTCRay& ray = rh.ray;
        ray.org_x = float(origin.x), ray.org_y = float(origin.y), ray.org_z = float(origin.z);
        ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
        ray.tnear = 0.0f;
        // Stops short of the light, so geometry touching it does not shadow it.
        ray.tfar = directional ? std::numeric_limits<float>::infinity()
                               : float(dist * (1.0 - 1e-4) - kOriginOffset);
        ray.mask = 0xffffffffu;
        bool occluded = false;
        if (settings.hitDistance) {
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &ctx, &rh);
            occluded = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            if (occluded) sumHit += double(ray.tfar), ++hits;
        } else {
            rtcOccluded1(scene, &ctx, &ray);
            occluded = ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
        }
        ++out.rays;
        sumG += g;
        if (!occluded) sumVG += g;
    }
    out.v = sumG > 0.0 ? float(sumVG / sumG) : 0.0f;
    out.hit = hits > 0 ? float(sumHit / hits) : 0.0f;
    return out;
}

}  // namespace

ShadowRayFrame ShadowRayTracer::trace(const ShadowRayGBuffer& gbuffer, const Light& light,
                                      const ShadowRaySettings& settings) const {
    const int W = gbuffer.width, H = gbuffer.height;
    ShadowRayFrame out;
    out.visibilityAndHit.assign(size_t(W) * size_t(H) * 2, 0.0f);
    std::vector<uint32_t> rays(size_t(W) * size_t(H), 0);
    const int threads =
        std::max(1, std::min(H, settings.threads > 0
                                    ? settings.threads
                                    : int(std::max(1u, std::thread::hardware_concurrency()))));
    auto rowsOf = [&](int t) {
        // Rows t, t + threads, ...: every pixel's result depends on the pixel alone.
        for (int y = t; y < H; y += threads)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y) * size_t(W) + size_t(x);
                const float* p = gbuffer.lsPosition + 4 * i;
                if (p[3] == 0.0f) continue;
                const float* n = gbuffer.lsNormal + 4 * i;
                const glm::dvec3 lsN = glm::normalize(glm::dvec3(n[0], n[1], n[2]));
                const PixelTrace r =
                    tracePixel(impl_->scene, light, impl_->frame, glm::dvec3(p[0], p[1], p[2]), lsN,
                               hashCombine(0x5eedu, uint32_t(i)), settings);
                out.visibilityAndHit[2 * i] = r.v;
                out.visibilityAndHit[2 * i + 1] = r.hit;
                rays[i] = r.rays;
            }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(rowsOf, t);
    rowsOf(0);
    for (std::thread& t : pool) t.join();
    for (uint32_t r : rays) out.raysTraced += r, out.pixelsTraced += r > 0 ? 1 : 0;
    return out;
}

}  // namespace so
