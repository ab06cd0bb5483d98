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

// The prior: kPrior pseudo-samples lit and kPrior shadowed at the mean weight. W: the total weight
// with them; Va: the estimate with them; share: their part of sum w^2 (v - Va)^2.
struct Prior {
    double W, Va, share;
};
Prior agrestiCoull(double sw, double swv, uint64_t nonZero) {
    const double wbar = sw / double(nonZero);
    const double W = sw + 2.0 * kPrior * wbar;
    const double Va = (swv + kPrior * wbar) / W;
    return {W, Va, kPrior * wbar * wbar * ((1.0 - Va) * (1.0 - Va) + Va * Va)};
}
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
    const Prior pr = agrestiCoull(sw, swv, nonZero);
    // sum w^2 (v - Va)^2 with v in {0, 1}: sw2v (1 - 2 Va) + Va^2 sw2, plus the prior's share.
    const double ss = sw2v * (1.0 - 2.0 * pr.Va) + pr.Va * pr.Va * sw2 + pr.share;
    e.stderr_ = std::sqrt(std::max(0.0, ss)) / pr.W;
    return e;
}

RatioEstimate replicaEstimate(const ReplicaSums& s) {
    double x = 0.0, y = 0.0;
    for (int j = 0; j < kReplicas; ++j) x += s.x[size_t(j)], y += s.y[size_t(j)];
    RatioEstimate e;
    if (s.nonZero == 0 || !(y > 0.0)) {
        e.stderr_ = 0.5;  // nothing measured: as uncertain as a [0, 1] quantity can be
        return e;
    }
    e.V = x / y;
    // Delta method over the replicas, which are independent: the ratio's variance from the
    // spread of the residuals x_j - V y_j, K - 1 degrees of freedom.
    double ss = 0.0;
    for (int j = 0; j < kReplicas; ++j) {
        const double r = s.x[size_t(j)] - e.V * s.y[size_t(j)];
        ss += r * r;
    }
    const double yMean = y / kReplicas;
    const double seReplicas = std::sqrt(ss / (kReplicas * (kReplicas - 1.0))) / yMean;
    // The prior's share of the iid estimate: it keeps "all samples agree" from meaning "certain",
    // and dominates only where the replicas barely differ.
    const Prior pr = agrestiCoull(y, x, s.nonZero);
    const double sePrior = std::sqrt(pr.share) / pr.W;
    // Stated as a standard error for the t quantile: half-width max(t se, z sePrior).
    e.stderr_ = std::max(seReplicas, kZ * sePrior / kIntervalQuantile95);
    return e;
}

namespace {

// One thread's packet and batch, reused pixel after pixel.
struct PacketState {
    RTCIntersectContext ctx;
    alignas(64) RTCRay16 ray;
    alignas(64) int valid[16];
    AreaBatch batch;
    // The current pixel's estimate after each packet: the stderr before the stopping guard, and
    // the stated half-width. Kept here so that no pixel allocates.
    std::vector<double> history;
    std::vector<float> halfWidths;
};

struct PixelResult {
    RatioEstimate est;
    int samples = 0;
    double efficiency = 0.0;  // Kish's n_eff / n of the weights
};

// The rounds the cost curve is read at: 1, 2, 3, 4, 6, 8, 12, ... up to `maxRounds`.
std::vector<int> curveRounds(int maxRounds) {
    std::vector<int> rounds;
    for (int p = 1; p <= maxRounds; p *= 2) {
        rounds.push_back(p);
        if (p >= 2 && p + p / 2 <= maxRounds) rounds.push_back(p + p / 2);
    }
    std::sort(rounds.begin(), rounds.end());
    if (rounds.empty() || rounds.back() != maxRounds) rounds.push_back(maxRounds);
    return rounds;
}

// One tile row's share of the curve, summed in row order afterwards (deterministic).
struct CurveRow {
    std::vector<uint64_t> samples;
    std::vector<double> halfWidthSum;
};

// `halfWidths`: one pixel's stated half-width after each packet.
void addToCurve(const std::vector<int>& rounds, const std::vector<float>& halfWidths,
                CurveRow& row) {
    if (halfWidths.empty()) return;
    for (size_t c = 0; c < rounds.size(); ++c) {
        const size_t k = std::min(size_t(rounds[c]), halfWidths.size());
        row.samples[c] += 16 * uint64_t(k);
        row.halfWidthSum[c] += halfWidths[k - 1];
    }
}

// One round: two points of each replica's own scrambled Sobol sequence (lanes 2j, 2j + 1 are
// replica j's points first, first + 1), traced as one packet, added to the replicas' sums.
void traceRound(const Accel& accel, const AreaLight& light, const AreaPixel& px,
                const uint32_t* replicaSeeds, uint32_t first, PacketState& p, ReplicaSums& sums,
                AreaShadowStats& st) {
    float su[16], sv[16];
    for (int j = 0; j < kReplicas; ++j)
        sobol2DBlock(first, kPointsPerRound, replicaSeeds[j], su + kPointsPerRound * j,
                     sv + kPointsPerRound * j);
    mapAreaBatch(light, px, su, sv, 16, p.batch);
    int active = 0;
    for (int k = 0; k < 16; ++k) {
        p.valid[k] = p.batch.weight[k] > 0.0f ? -1 : 0;
        active += p.valid[k] != 0;
        p.ray.dir_x[k] = p.batch.dirX[k];
        p.ray.dir_y[k] = p.batch.dirY[k];
        p.ray.dir_z[k] = p.batch.dirZ[k];
        p.ray.tfar[k] = p.batch.tfar[k];
    }
    if (active) rtcOccluded16(p.valid, accel.rtcScene(), &p.ctx, &p.ray);
    for (int k = 0; k < 16; ++k) {
        if (!p.valid[k]) continue;
        const double w = p.batch.weight[k];
        const double v = p.ray.tfar[k] >= 0.0f ? 1.0 : 0.0;  // -inf on a hit
        sums.x[size_t(k / kPointsPerRound)] += w * v;
        sums.y[size_t(k / kPointsPerRound)] += w;
        sums.sw2 += w * w;
        sums.sw2v += w * w * v;
        st.raysOccluded += v == 0.0;
    }
    sums.nonZero += uint64_t(active);
    st.raysTraced += uint64_t(active);
}

// Rounds of 16 samples until the pixel's 95% half-width is at most the target (checked from
// kMinAdaptiveSpp on), or its budget is spent; with a fixed count, exactly that many (rounded up
// to whole rounds).
PixelResult samplePixel(const Accel& accel, const AreaLight& light, const AreaPixel& px,
                        const AreaSampling& sampling, uint32_t pixelSeed, const glm::vec3& org,
                        uint32_t originId, PacketState& p, AreaShadowStats& st) {
    for (int k = 0; k < 16; ++k) {
        p.ray.org_x[k] = org.x;
        p.ray.org_y[k] = org.y;
        p.ray.org_z[k] = org.z;
        p.ray.tnear[k] = 0.0f;
        p.ray.time[k] = 0.0f;
        p.ray.mask[k] = 0xFFFFFFFFu;
        p.ray.flags[k] = 0;
        p.ray.id[k] = originId;  // the filter skips this triangle
    }
    uint32_t replicaSeeds[kReplicas];
    for (int j = 0; j < kReplicas; ++j) replicaSeeds[j] = hashCombine(pixelSeed, uint32_t(j));
    const int maxSpp = sampling.fixedSpp > 0 ? sampling.fixedSpp : sampling.maxSpp;
    ReplicaSums sums;
    PixelResult r;
    std::vector<double>& history = p.history;
    p.history.clear();
    p.halfWidths.clear();
    for (uint32_t first = 0;; first += kPointsPerRound) {
        traceRound(accel, light, px, replicaSeeds, first, p, sums, st);
        r.samples += 16;
        r.est = replicaEstimate(sums);
        history.push_back(r.est.stderr_);
        // Eight replicas estimate the spread roughly (27% relative error): an adaptive pixel must
        // not stop on a lucky low estimate, so the one of half as many samples, scaled by
        // RQMC's N^-0.75 for edges, bounds it from below (a fixed count has no stopping to bias).
        const size_t half = history.size() / 2;
        if (sampling.fixedSpp == 0 && half >= 1)
            r.est.stderr_ =
                std::max(r.est.stderr_,
                         history[half - 1] * std::pow(double(half) / double(history.size()), 0.75));
        p.halfWidths.push_back(float(kIntervalQuantile95 * r.est.stderr_));
        if (r.samples >= maxSpp) break;
        if (sampling.fixedSpp == 0 && r.samples >= kMinAdaptiveSpp &&
            kIntervalQuantile95 * r.est.stderr_ <= sampling.targetError)
            break;
    }
    double sw = 0.0;
    for (double y : sums.y) sw += y;
    if (sums.sw2 > 0.0) r.efficiency = sw * sw / (sums.sw2 * double(sums.nonZero));
    return r;
}

// One light's sampling over the image: what every pixel reads and writes, and the per-slot and
// per-row records that are reduced in a fixed order afterwards (so the statistics do not depend on
// the thread count).
struct AreaRun {
    const Accel& accel;
    const SurfaceBuffer& sb;
    const AreaLight& light;
    const AreaSampling& sampling;
    uint32_t stream;
    float *V, *stderr_, *spp, *cosine, *unconverged;
    std::vector<int> rounds;
    std::vector<float> perSampleVar, halfWidth;  // per slot
    std::vector<double> efficiency;              // per slot
    std::vector<CurveRow> curveRows;             // per tile row

    void pixel(size_t s, int ty, PacketState& packet, AreaShadowStats& st);
    void reduceSlots(AreaShadowStats& total) const;
    void reduceCurve(AreaShadowStats& total) const;
};

void AreaRun::pixel(size_t s, int ty, PacketState& packet, AreaShadowStats& st) {
    const size_t px = sb.pixelOfSlot(s);
    if (px == SIZE_MAX) return;
    V[px] = stderr_[px] = spp[px] = cosine[px] = 0.0f;
    if (!sb.hit[s]) {
        ++st.skippedBackground;
        return;
    }
    const glm::vec3 p = sb.lsPoint(s), n = sb.lsNormal(s);
    cosine[px] = glm::dot(n, glm::normalize(light.lsCenter - p));
    switch (classifyAreaPixel(light, glm::dvec3(p), glm::dvec3(n))) {
        case AreaSkip::BelowHorizon:
            ++st.skippedBelowHorizon;
            return;
        case AreaSkip::BehindLight:
            ++st.skippedBehindLight;
            return;
        case AreaSkip::InsideLight:
            ++st.skippedInsideLight;
            return;
        case AreaSkip::None:
            break;
    }
    ++st.pixelsSampled;
    const PixelResult r = samplePixel(accel, light, prepareAreaPixel(light, p, n), sampling,
                                      areaPixelSeed(sampling.seed, stream, uint32_t(px)),
                                      sb.lsRayOrigin(s), sb.originId[s], packet, st);
    V[px] = float(r.est.V);
    stderr_[px] = float(r.est.stderr_);
    spp[px] = float(r.samples);
    addToCurve(rounds, packet.halfWidths, curveRows[size_t(ty)]);
    const double hw = kIntervalQuantile95 * r.est.stderr_;
    st.samples += uint64_t(r.samples);
    st.maxSpp = std::max<uint64_t>(st.maxSpp, uint64_t(r.samples));
    st.reachedTarget += hw <= sampling.targetError;
    if (sampling.fixedSpp == 0 && hw > sampling.targetError) {
        ++st.pixelsUnconverged;
        if (unconverged) unconverged[px] = 1.0f;
    }
    halfWidth[s] = float(hw);
    perSampleVar[s] = float(r.est.stderr_ * r.est.stderr_ * double(r.samples));
    efficiency[s] = r.efficiency;
}

// Reductions over the per-slot arrays, in slot order.
void AreaRun::reduceSlots(AreaShadowStats& total) const {
    double efficiencySum = 0.0;
    for (double e : efficiency) efficiencySum += e;
    for (float h : halfWidth) total.worstHalfWidth = std::max(total.worstHalfWidth, double(h));
    if (total.worstHalfWidth > 0.0)
        for (float v : perSampleVar)
            total.uniformSppForWorst =
                std::max(total.uniformSppForWorst,
                         std::ceil(kIntervalQuantile95 * kIntervalQuantile95 * double(v) /
                                   (total.worstHalfWidth * total.worstHalfWidth)));
    total.samplingEfficiency =
        total.pixelsSampled ? efficiencySum / double(total.pixelsSampled) : 1.0;
}

// The cost curve from the rows, in row order, and the run as it ended.
void AreaRun::reduceCurve(AreaShadowStats& total) const {
    const int roundsUsed = int((total.maxSpp + 15) / 16);
    for (size_t c = 0; c < rounds.size() && rounds[c] <= roundsUsed && total.pixelsSampled; ++c) {
        CostPoint point{rounds[c], 0, 0.0};
        for (const CurveRow& row : curveRows) {
            point.samples += row.samples[c];
            point.meanHalfWidth += row.halfWidthSum[c];
        }
        point.meanHalfWidth /= double(total.pixelsSampled);
        total.costCurve.push_back(point);
    }
    if (total.pixelsSampled &&
        (total.costCurve.empty() || total.costCurve.back().rounds < roundsUsed)) {
        double sum = 0.0;
        for (float h : halfWidth) sum += h;
        total.costCurve.push_back({roundsUsed, total.samples, sum / double(total.pixelsSampled)});
    }
}

void addCounts(AreaShadowStats& total, const AreaShadowStats& s) {
    total.samples += s.samples;
    total.raysTraced += s.raysTraced;
    total.raysOccluded += s.raysOccluded;
    total.pixelsSampled += s.pixelsSampled;
    total.reachedTarget += s.reachedTarget;
    total.pixelsUnconverged += s.pixelsUnconverged;
    total.pixelsWithoutUsableSamples += s.pixelsWithoutUsableSamples;
    total.maxSpp = std::max(total.maxSpp, s.maxSpp);
    total.skippedBackground += s.skippedBackground;
    total.skippedBelowHorizon += s.skippedBelowHorizon;
    total.skippedBehindLight += s.skippedBehindLight;
    total.skippedInsideLight += s.skippedInsideLight;
}

}  // namespace

AreaShadowStats traceAreaShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const AreaLight& light, const AreaSampling& sampling,
                                 uint32_t stream, float* V, float* stderr_, float* spp,
                                 float* cosine, float* unconverged, Progress* progress) {
    auto t0 = std::chrono::steady_clock::now();
    const int maxSpp = sampling.fixedSpp > 0 ? sampling.fixedSpp : sampling.maxSpp;
    const std::vector<int> rounds = curveRounds((maxSpp + 15) / 16);
    AreaRun run{
        accel,
        sb,
        light,
        sampling,
        stream,
        V,
        stderr_,
        spp,
        cosine,
        unconverged,
        rounds,
        std::vector<float>(sb.slotCount(), 0.0f),
        std::vector<float>(sb.slotCount(), 0.0f),
        std::vector<double>(sb.slotCount(), 0.0),
        std::vector<CurveRow>(size_t(sb.tilesY), {std::vector<uint64_t>(rounds.size(), 0),
                                                  std::vector<double>(rounds.size(), 0.0)})};
    tbb::combinable<AreaShadowStats> partial;
    tbb::parallel_for(
        tbb::blocked_range<int>(0, sb.tilesY, 1), [&](const tbb::blocked_range<int>& range) {
            setEmbreeFloatMode();
            AreaShadowStats& st = partial.local();
            PacketState packet;
            rtcInitIntersectContext(&packet.ctx);
            packet.ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            for (int ty = range.begin(); ty != range.end(); ++ty) {
                for (size_t s = size_t(ty) * size_t(sb.tilesX) * 16;
                     s < size_t(ty + 1) * size_t(sb.tilesX) * 16; ++s)
                    run.pixel(s, ty, packet, st);
                if (progress)
                    progress->advance(uint64_t(SurfaceBuffer::kTile) * uint64_t(sb.width));
            }
        });
    AreaShadowStats total;
    partial.combine_each([&](const AreaShadowStats& s) { addCounts(total, s); });
    run.reduceSlots(total);
    run.reduceCurve(total);
    total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return total;
}

}  // namespace so
