#include "oracle/hard_shadow.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/progress.h"
#include "oracle/offset.h"

namespace so {

HardLight makeHardLight(const Light& light, const LocalFrame& frame) {
    HardLight h;
    h.type = light.type;
    h.lsPosition = frame.lsFromWs(light.wsPosition);
    h.lsDirection = glm::normalize(light.wsDirection);
    if (light.type == LightType::Spot)
        h.cosOuter = std::cos(light.outerConeDeg * std::numbers::pi / 180.0);
    if (light.type != LightType::Directional) h.lsEndMargin = offsetMargin(glm::vec3(h.lsPosition));
    h.lsPositionF = glm::vec3(h.lsPosition);
    h.lsDirectionF = glm::vec3(h.lsDirection);
    h.cosOuterF = float(h.cosOuter);
    return h;
}

ShadowRaySetup setupShadowRay(const SurfaceBuffer& sb, size_t slot, const HardLight& light) {
    ShadowRaySetup s;
    if (!sb.hit[slot]) return s;
    const glm::dvec3 n(sb.lsNormal[slot]);
    if (light.type == LightType::Directional) {
        s.cosine = -glm::dot(n, light.lsDirection);
        if (!(s.cosine > 0.0)) {
            s.kind = ShadowRayKind::Attached;
            return s;
        }
        s.kind = ShadowRayKind::Traced;
        s.org = sb.lsRayOrigin[slot];
        s.dir = glm::vec3(-light.lsDirection);
        s.tfar = std::numeric_limits<float>::infinity();
        return s;
    }
    // From the surface point, not the offset origin: the origin sits up to 256 ulp above the
    // surface along the normal, which at grazing incidence would lower the cosine by as much as
    // the cosine itself. Float is enough here (the cosine's error is ~1e-7, a hundred times below
    // the grazing angles the tests check) and keeps this per-ray setup cheap: it bounds the
    // oracle's throughput (bench/).
    const glm::vec3 toLight = light.lsPositionF - sb.lsPoint[slot];
    const float dist = std::sqrt(glm::dot(toLight, toLight));
    const glm::vec3 w = toLight * (1.0f / dist);
    s.cosine = glm::dot(sb.lsNormal[slot], w);
    if (!(s.cosine > 0.0)) {
        s.kind = ShadowRayKind::Attached;
        return s;
    }
    if (light.type == LightType::Spot && -glm::dot(w, light.lsDirectionF) < light.cosOuterF) {
        s.kind = ShadowRayKind::OutsideCone;
        return s;
    }
    s.kind = ShadowRayKind::Traced;
    s.org = sb.lsRayOrigin[slot];
    // Aimed along the surface point's direction: from the offset origin the ray then ends within
    // the offset of the light, which the doubled end margin allows for.
    s.dir = w;
    s.tfar = std::max(0.0f, dist - 2.0f * light.lsEndMargin);
    return s;
}

HardShadowStats traceHardShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const HardLight& light, float* V, float* cosine,
                                 Progress* progress) {
    auto t0 = std::chrono::steady_clock::now();
    tbb::combinable<HardShadowStats> partial;

    tbb::parallel_for(
        tbb::blocked_range<int>(0, sb.tilesY), [&](const tbb::blocked_range<int>& range) {
            setEmbreeFloatMode();
            HardShadowStats& st = partial.local();
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            alignas(64) RTCRay16 ray;
            alignas(64) int valid[16];
            size_t lanePixel[16];
            for (int ty = range.begin(); ty != range.end(); ++ty) {
                for (int tx = 0; tx < sb.tilesX; ++tx) {
                    const size_t base = (size_t(ty) * size_t(sb.tilesX) + size_t(tx)) * 16;
                    const int x0 = tx * SurfaceBuffer::kTile, y0 = ty * SurfaceBuffer::kTile;
                    int active = 0;
                    for (int k = 0; k < 16; ++k) {
                        valid[k] = 0;
                        const int x = x0 + (k & 3), y = y0 + (k >> 2);
                        if (x >= sb.width || y >= sb.height) continue;
                        const size_t pixel = size_t(y) * size_t(sb.width) + size_t(x);
                        const ShadowRaySetup s = setupShadowRay(sb, base + size_t(k), light);
                        cosine[pixel] = float(s.cosine);
                        V[pixel] = 0.0f;
                        switch (s.kind) {
                            case ShadowRayKind::Background:
                                ++st.skippedBackground;
                                continue;
                            case ShadowRayKind::Attached:
                                ++st.skippedAttached;
                                continue;
                            case ShadowRayKind::OutsideCone:
                                ++st.skippedOutsideCone;
                                continue;
                            case ShadowRayKind::Traced:
                                break;
                        }
                        valid[k] = -1;
                        lanePixel[k] = pixel;
                        ray.org_x[k] = s.org.x;
                        ray.org_y[k] = s.org.y;
                        ray.org_z[k] = s.org.z;
                        ray.dir_x[k] = s.dir.x;
                        ray.dir_y[k] = s.dir.y;
                        ray.dir_z[k] = s.dir.z;
                        ray.tnear[k] = 0.0f;
                        ray.tfar[k] = s.tfar;
                        ray.time[k] = 0.0f;
                        ray.mask[k] = 0xFFFFFFFFu;
                        ray.id[k] = unsigned(pixel);
                        ray.flags[k] = 0;
                        ++active;
                    }
                    if (!active) continue;
                    rtcOccluded16(valid, accel.rtcScene(), &ctx, &ray);
                    for (int k = 0; k < 16; ++k) {
                        if (!valid[k]) continue;
                        // Embree sets tfar to -inf on a hit.
                        const bool lit = ray.tfar[k] >= 0.0f;
                        V[lanePixel[k]] = lit ? 1.0f : 0.0f;
                        st.occluded += lit ? 0 : 1;
                    }
                    st.traced += uint64_t(active);
                }
                if (progress)
                    progress->advance(uint64_t(SurfaceBuffer::kTile) * uint64_t(sb.width));
            }
        });
    HardShadowStats total;
    partial.combine_each([&](const HardShadowStats& s) {
        total.traced += s.traced;
        total.occluded += s.occluded;
        total.skippedBackground += s.skippedBackground;
        total.skippedAttached += s.skippedAttached;
        total.skippedOutsideCone += s.skippedOutsideCone;
    });
    total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return total;
}

}  // namespace so
