#include "oracle/area_shadow.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/progress.h"
#include "oracle/sobol.h"

namespace so {

namespace {
constexpr double kZ = kZ95;
constexpr double kPrior = 0.5 * kZ * kZ;  // Agresti-Coull: z^2/2 pseudo-samples each way
}  // namespace

uint32_t areaPixelSeed(uint32_t seed, uint32_t stream, uint32_t pixel) {
    return hashCombine(hashCombine(seed, stream), pixel);
}

RatioEstimate ratioEstimate(double sw, double swv, double sw2, double sw2v, uint64_t nonZero) {
    RatioEstimate e;
    if (nonZero == 0 || !(sw > 0.0)) {
        e.V = 0.0;
        e.stderr_ = 0.5;  // nothing measured: as uncertain as a [0, 1] quantity can be
        return e;
    }
    e.V = swv / sw;
    const double wbar = sw / double(nonZero);
    const double W = sw + 2.0 * kPrior * wbar;
    const double Va = (swv + kPrior * wbar) / W;
    // sum w^2 (v - Va)^2 with v in {0, 1}: sw2v (1 - 2 Va) + Va^2 sw2, plus the prior's share.
    const double ss = sw2v * (1.0 - 2.0 * Va) + Va * Va * sw2 +
                      kPrior * wbar * wbar * ((1.0 - Va) * (1.0 - Va) + Va * Va);
    e.stderr_ = std::sqrt(std::max(0.0, ss)) / W;
    return e;
}

AreaShadowStats traceAreaShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const AreaLight& light, const AreaSampling& sampling,
                                 uint32_t stream, float* V, float* stderr_, float* spp,
                                 float* cosine, Progress* progress) {
    auto t0 = std::chrono::steady_clock::now();
    struct Partial {
        AreaShadowStats st;
    };
    tbb::combinable<Partial> partial;
    // Per-pixel per-sample variance and half-width, for the uniform-run estimate, and sampling
    // efficiency: reduced in slot order afterwards, so the sums do not depend on the threads.
    std::vector<float> perSampleVar(sb.slotCount(), 0.0f), halfWidth(sb.slotCount(), 0.0f);
    std::vector<double> efficiency(sb.slotCount(), 0.0);
    const int maxSpp = sampling.fixedSpp > 0 ? sampling.fixedSpp : sampling.maxSpp;

    tbb::parallel_for(
        tbb::blocked_range<int>(0, sb.tilesY, 1), [&](const tbb::blocked_range<int>& range) {
            setEmbreeFloatMode();
            Partial& part = partial.local();
            AreaShadowStats& st = part.st;
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            alignas(64) RTCRay16 ray;
            alignas(64) int valid[16];
            AreaBatch batch;
            for (int ty = range.begin(); ty != range.end(); ++ty) {
                for (size_t s = size_t(ty) * size_t(sb.tilesX) * 16;
                     s < size_t(ty + 1) * size_t(sb.tilesX) * 16; ++s) {
                    const size_t pixel = sb.pixelOfSlot(s);
                    if (pixel == SIZE_MAX) continue;
                    V[pixel] = 0.0f;
                    stderr_[pixel] = 0.0f;
                    spp[pixel] = 0.0f;
                    cosine[pixel] = 0.0f;
                    if (!sb.hit[s]) {
                        ++st.skippedBackground;
                        continue;
                    }
                    const glm::vec3 p = sb.lsPoint(s), n = sb.lsNormal(s), org = sb.lsRayOrigin(s);
                    cosine[pixel] = glm::dot(n, glm::normalize(light.lsCenter - p));
                    switch (classifyAreaPixel(light, glm::dvec3(p), glm::dvec3(n))) {
                        case AreaSkip::BelowHorizon:
                            ++st.skippedBelowHorizon;
                            continue;
                        case AreaSkip::BehindLight:
                            ++st.skippedBehindLight;
                            continue;
                        case AreaSkip::InsideLight:
                            ++st.skippedInsideLight;
                            continue;
                        case AreaSkip::None:
                            break;
                    }
                    ++st.pixelsSampled;
                    const AreaPixel px = prepareAreaPixel(light, p, n);
                    const uint32_t pixelSeed =
                        areaPixelSeed(sampling.seed, stream, uint32_t(pixel));
                    for (int k = 0; k < 16; ++k) {
                        ray.org_x[k] = org.x;
                        ray.org_y[k] = org.y;
                        ray.org_z[k] = org.z;
                        ray.tnear[k] = 0.0f;
                        ray.time[k] = 0.0f;
                        ray.mask[k] = 0xFFFFFFFFu;
                        ray.flags[k] = 0;
                        ray.id[k] = sb.originId[s];  // the filter skips this triangle
                    }
                    double sw = 0, swv = 0, sw2 = 0, sw2v = 0;
                    uint64_t nonZero = 0;
                    int n_ = 0;
                    RatioEstimate est;
                    while (true) {
                        const int count = std::min(16, maxSpp - n_);
                        sampleAreaBatch(light, px, pixelSeed, uint32_t(n_), count, batch);
                        int active = 0;
                        for (int k = 0; k < 16; ++k) {
                            valid[k] = batch.weight[k] > 0.0f ? -1 : 0;
                            active += valid[k] != 0;
                            ray.dir_x[k] = batch.dirX[k];
                            ray.dir_y[k] = batch.dirY[k];
                            ray.dir_z[k] = batch.dirZ[k];
                            ray.tfar[k] = batch.tfar[k];
                        }
                        if (active) rtcOccluded16(valid, accel.rtcScene(), &ctx, &ray);
                        for (int k = 0; k < 16; ++k) {
                            if (!valid[k]) continue;
                            const double w = batch.weight[k];
                            const double v = ray.tfar[k] >= 0.0f ? 1.0 : 0.0;  // -inf on a hit
                            sw += w;
                            swv += w * v;
                            sw2 += w * w;
                            sw2v += w * w * v;
                            st.raysOccluded += v == 0.0;
                        }
                        nonZero += uint64_t(active);
                        st.raysTraced += uint64_t(active);
                        n_ += count;
                        est = ratioEstimate(sw, swv, sw2, sw2v, nonZero);
                        if (n_ >= maxSpp) break;
                        if (sampling.fixedSpp == 0 && kZ * est.stderr_ <= sampling.targetError)
                            break;
                    }
                    V[pixel] = float(est.V);
                    stderr_[pixel] = float(est.stderr_);
                    spp[pixel] = float(n_);
                    st.samples += uint64_t(n_);
                    st.maxSpp = std::max<uint64_t>(st.maxSpp, uint64_t(n_));
                    st.reachedTarget += kZ * est.stderr_ <= sampling.targetError;
                    halfWidth[s] = float(kZ * est.stderr_);
                    perSampleVar[s] = float(est.stderr_ * est.stderr_ * double(n_));
                    if (sw2 > 0.0) efficiency[s] = sw * sw / (sw2 * double(nonZero));
                }
                if (progress)
                    progress->advance(uint64_t(SurfaceBuffer::kTile) * uint64_t(sb.width));
            }
        });

    AreaShadowStats total;
    partial.combine_each([&](const Partial& p) {
        const AreaShadowStats& s = p.st;
        total.samples += s.samples;
        total.raysTraced += s.raysTraced;
        total.raysOccluded += s.raysOccluded;
        total.pixelsSampled += s.pixelsSampled;
        total.reachedTarget += s.reachedTarget;
        total.pixelsWithoutUsableSamples += s.pixelsWithoutUsableSamples;
        total.maxSpp = std::max(total.maxSpp, s.maxSpp);
        total.skippedBackground += s.skippedBackground;
        total.skippedBelowHorizon += s.skippedBelowHorizon;
        total.skippedBehindLight += s.skippedBehindLight;
        total.skippedInsideLight += s.skippedInsideLight;
    });
    // Reductions over the per-slot arrays run in slot order: independent of the thread count.
    double efficiencySum = 0.0;
    for (double e : efficiency) efficiencySum += e;
    for (float h : halfWidth) total.worstHalfWidth = std::max(total.worstHalfWidth, double(h));
    if (total.worstHalfWidth > 0.0)
        for (float v : perSampleVar)
            total.uniformSppForWorst = std::max(
                total.uniformSppForWorst,
                std::ceil(kZ * kZ * double(v) / (total.worstHalfWidth * total.worstHalfWidth)));
    total.samplingEfficiency =
        total.pixelsSampled ? efficiencySum / double(total.pixelsSampled) : 1.0;
    total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return total;
}

}  // namespace so
