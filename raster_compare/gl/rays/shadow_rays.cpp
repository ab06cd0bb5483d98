#include "raster_compare/gl/rays/shadow_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/lights/light_kind.h"
#include "core/sobol.h"
#include "embree/embree_handles.h"
#include "embree/triangle_scene.h"
#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

// The offset of a ray's origin from the surface, in local units (the scene fits in [-1, 1]):
// above float rounding of the positions the camera pass interpolated.
constexpr double kOriginOffset = 2e-4;

// The BVH of the shadow rays: Embree's plain build (no robust mode, medium quality, triangles
// kept as the scene gives them), as a GPU's RT cores would take the raster path's own meshes,
// not the oracle's watertight one; alpha-tested meshes cut their masks' holes as the oracle's
// do, with no origin triangle to skip (the origin is offset instead).
TriangleSceneOptions rasterBuild() {
    TriangleSceneOptions o;
    o.robust = false;
    o.contextFilter = false;
    o.quality = RTC_BUILD_QUALITY_MEDIUM;
    o.dropDegenerates = false;
    o.alphaSkipsOrigin = false;
    return o;
}

}  // namespace

struct ShadowRayTracer::Impl {
    Impl(const Scene& scene, const LocalFrame& lsFrame)
        : frame(lsFrame),
          device("threads=1"),  // the BVH build; the rays use threads of their own
          triangles(scene, frame, device, rasterBuild()) {}
    LocalFrame frame;
    EmbreeDevice device;
    TriangleScene triangles;
};

ShadowRayTracer::ShadowRayTracer(const Scene& scene, const LocalFrame& frame)
    : impl_(std::make_unique<Impl>(scene, frame)) {}

ShadowRayTracer::~ShadowRayTracer() = default;

namespace {

struct PixelTrace {
    float v = 0.0f, hit = 0.0f;
    uint32_t rays = 0;
};

// The light's sample for the pixel's own scrambled sequence at index `index`, as the point lsP
// sees the light (its kind says how: raster_light_kind.h, pointSeenFrom), local frame.
// lsEmitNormal is the emitter's normal there (zero for lights that are a point or a direction): a
// direction, the same in both frames (the local frame only scales by a power of two and moves).
struct LightSample {
    glm::dvec3 lsPoint{0.0}, lsEmitNormal{0.0};
};

LightSample sampleLight(const RasterLightKind& kind, const Light& light, const LocalFrame& frame,
                        const glm::dvec3& lsP, uint32_t index, uint32_t seed) {
    float u = 0.0f, v = 0.0f;
    sobol2D(index, seed, u, v);
    const LightPoint p = kind.pointSeenFrom(light, frame.wsFromLs(lsP), double(u), double(v));
    return {frame.lsFromWs(p.wsPoint), p.wsNormal};
}

// One pixel: `count` of the spp rays from the offset point, V = sum(v G) / sum(G).
PixelTrace tracePixel(RTCScene scene, const Light& light, const LocalFrame& frame,
                      const glm::dvec3& lsP, const glm::dvec3& lsN, uint32_t pixelSeed, int count,
                      const ShadowRaySettings& settings) {
    PixelTrace out;
    const RasterLightKind& kind = rasterLightKind(light.type);
    const bool directional = isDirectional(light);
    const bool area = kind.area() != nullptr;
    const glm::dvec3 origin = lsP + kOriginOffset * lsN;
    double sumG = 0.0, sumVG = 0.0, sumHit = 0.0;
    int hits = 0;
    for (int s = 0; s < count; ++s) {
        const LightSample ls = sampleLight(
            kind, light, frame, lsP,
            uint32_t(settings.frameIndex) * uint32_t(settings.spp) + uint32_t(s), pixelSeed);
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
                const int count = settings.samplesPerPixel
                                      ? std::min(int((*settings.samplesPerPixel)[i]), settings.spp)
                                      : settings.spp;
                if (count == 0) continue;
                const float* n = gbuffer.lsNormal + 4 * i;
                const glm::dvec3 lsN = glm::normalize(glm::dvec3(n[0], n[1], n[2]));
                const PixelTrace r = tracePixel(impl_->triangles.rtcScene(), light, impl_->frame,
                                                glm::dvec3(p[0], p[1], p[2]), lsN,
                                                hashCombine(0x5eedu, uint32_t(i)), count, settings);
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
