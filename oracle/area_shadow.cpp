#include "oracle/area_shadow.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <tbb/combinable.h>
#include <glm/geometric.hpp>

#include "core/progress.h"
#include "core/sobol.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/near_field.h"
#include "oracle/sse_lanes.h"
#include "oracle/tile_rows.h"

namespace so {

uint32_t areaPixelSeed(uint32_t seed, uint32_t stream, uint32_t pixel) {
    return hashCombine(hashCombine(seed, stream), pixel);
}

ReplicaSeeds replicaSeeds(uint32_t pixelSeed) {
    ReplicaSeeds seeds;
    for (int k = 0; k < 16; ++k) {
        const uint32_t replica = hashCombine(pixelSeed, uint32_t(k / kPointsPerRound));
        seeds.u[k] = sobolScrambleU(replica);
        seeds.v[k] = sobolScrambleV(replica);
    }
    return seeds;
}

namespace {

// The 16 lanes' scrambled points from their bit-reversed unscrambled values (lane k uses
// rev[k % kPointsPerRound]). Integer work only, exact on any instruction set: the clones for
// SSE4.1 and AVX2 (32-bit multiplies in vector registers) are picked at run time and give the very
// same bits.
__attribute__((target_clones("avx2", "sse4.1", "default"))) void scrambledPoints(
    const uint32_t* revU, const uint32_t* revV, const ReplicaSeeds& seeds, float* su, float* sv) {
    for (int k = 0; k < 16; ++k) {
        const int i = k % kPointsPerRound;
        su[k] = sobolFloat(reverseBits32(laineKarras(revU[i], seeds.u[k])));
        sv[k] = sobolFloat(reverseBits32(laineKarras(revV[i], seeds.v[k])));
    }
}

}  // namespace

void sampleRound(const AreaLight& light, const AreaPixel& px, const ReplicaSeeds& seeds,
                 uint32_t first, AreaBatch& b) {
    // Points first .. first + kPointsPerRound - 1 of every replica's sequence: sobol2DBlock's
    // values. owenScramble(x) = reverse(lk(reverse(x))), and the unscrambled points' reversed
    // bits are first ^ i and reverse(sobol1(first)) ^ reverse(d1[i]), so one bit reversal per
    // value is left.
    uint32_t revU[kPointsPerRound], revV[kPointsPerRound];
    const uint32_t revV0 = reverseBits32(sobol1(first));
    for (int i = 0; i < kPointsPerRound; ++i) {
        revU[i] = first ^ uint32_t(i);
        revV[i] = revV0 ^ reverseBits32(kSobolBlock1[i]);
    }
    alignas(64) float su[16], sv[16];
    scrambledPoints(revU, revV, seeds, su, sv);
    mapAreaBatch(light, px, su, sv, 16, b);
}

namespace {

// One thread's packet and batch, reused pixel after pixel.
struct PacketState {
    ShadowContext ctx;
    alignas(64) RTCRay16 ray;
    alignas(64) int valid[16];
    AreaBatch batch;
    // The current pixel's estimate after each packet: the stderr before the stopping guard, and
    // the stated half-width. Kept here so that no pixel allocates.
    std::vector<double> history;
    std::vector<float> halfWidths;
    FacingCache facingCache;  // the last exact decision (classifyAreaPixel)
    // The current pixel's near field (near_field.h), its triangles the segments to the light can
    // reach (each holds the point in double where the pixel's true segments start), and where
    // Embree starts the pixel's rays when there are some (nearTnear).
    std::vector<uint32_t> nearIds;
    std::vector<NearTriangle> nearTriangles;
    float nearTnear = 0.0f;
};

struct PixelResult {
    RatioEstimate est;
    int samples = 0;
    bool agreeing = false;   // every sample lit, or every sample shadowed
    double threshold = 0.0;  // the half-width the stopping rule asked for
    // Adaptive: the half-width the stopping rule predicted from the decision half (infinite
    // where the budget ran out before it reached the threshold).
    double decisionHalfWidth = std::numeric_limits<double>::infinity();
    double efficiency = 0.0;  // Kish's n_eff / n of the weights
};

// Whether the cost curve reads round n (curveRounds, before the last).
bool onCostCurve(int n) {
    const int m = n % 3 == 0 ? n / 3 : n;
    return (m & (m - 1)) == 0;
}

// The guard's scale at round n: (floor(n / 2) / n)^0.75, from a table (a pow per round would
// cost a few percent of the pass).
double guardScale(int n) {
    static const std::vector<double> table = [] {
        std::vector<double> t(4097);
        for (size_t k = 1; k < t.size(); ++k) t[k] = std::pow(double(k / 2) / double(k), 0.75);
        return t;
    }();
    return size_t(n) < table.size() ? table[size_t(n)] : std::pow(double(n / 2) / double(n), 0.75);
}

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
    std::vector<double> penumbraHalfWidthSum;  // over the penumbra's pixels (CostPoint)
    uint64_t penumbraPixels = 0;
};

// `halfWidths`: one pixel's stated half-width after each packet; `penumbra`: its V ended strictly
// between 0 and 1.
void addToCurve(const std::vector<int>& rounds, const std::vector<float>& halfWidths, bool penumbra,
                CurveRow& row) {
    if (halfWidths.empty()) return;
    row.penumbraPixels += penumbra ? 1 : 0;
    for (size_t c = 0; c < rounds.size(); ++c) {
        const size_t k = std::min(size_t(rounds[c]), halfWidths.size());
        row.samples[c] += 16 * uint64_t(k);
        row.halfWidthSum[c] += halfWidths[k - 1];
        if (penumbra) row.penumbraHalfWidthSum[c] += halfWidths[k - 1];
    }
}

// The lanes Embree left lit, against the pixel's near field in double: the true segment from the
// surface point, which the origin offset does not move (near_field.h).
void decideNearField(PacketState& p, AreaShadowStats& st) {
    for (int k = 0; k < 16; ++k) {
        if (!p.valid[k] || !(p.ray.tfar[k] >= 0.0f)) continue;
        const glm::dvec3 dir(p.batch.dirX[k], p.batch.dirY[k], p.batch.dirZ[k]);
        ++st.nearFieldRays;
        const double tMax = double(p.batch.tfar[k]);
        if (nearFirstHit(p.nearTriangles.data(), p.nearTriangles.size(), dir, tMax) < tMax) {
            p.ray.tfar[k] = -std::numeric_limits<float>::infinity();
            ++st.nearFieldOccluded;
        }
    }
}

// One round: two points of each replica's own scrambled Sobol sequence (lanes 2j, 2j + 1 are
// replica j's points first, first + 1), traced as one packet, added to the replicas' sums.
// `tangentCos`: the pixel's tangency bound (offset.h); a round holding a ray below it runs the
// origin filter.
void traceRound(const Accel& accel, const AreaLight& light, const AreaPixel& px,
                const ReplicaSeeds& seeds, uint32_t first, float tangentCos, PacketState& p,
                ReplicaSums& sums, AreaShadowStats& st) {
    sampleRound(light, px, seeds, first, p.batch);
    // The lanes with weight are traced; the packet runs the filter where one of them leaves
    // within the tangency bound (a NaN cosine counts as within). Four lanes at a time
    // (sse_lanes.h).
    int active = 0;
    __m128 nearLanes = _mm_setzero_ps();
    for (int g = 0; g < 16; g += 4) {
        const __m128 on = _mm_cmpgt_ps(_mm_load_ps(p.batch.weight + g), _mm_setzero_ps());
        _mm_store_si128(reinterpret_cast<__m128i*>(p.valid + g), _mm_castps_si128(on));
        const __m128 clear = _mm_cmpge_ps(_mm_load_ps(p.batch.cosine + g), _mm_set1_ps(tangentCos));
        nearLanes = _mm_or_ps(nearLanes, _mm_andnot_ps(clear, on));
        active += setBits4(_mm_movemask_ps(on));
    }
    const bool near = _mm_movemask_ps(nearLanes) != 0;
    std::memcpy(p.ray.dir_x, p.batch.dirX, sizeof p.batch.dirX);
    std::memcpy(p.ray.dir_y, p.batch.dirY, sizeof p.batch.dirY);
    std::memcpy(p.ray.dir_z, p.batch.dirZ, sizeof p.batch.dirZ);
    std::memcpy(p.ray.tfar, p.batch.tfar, sizeof p.batch.tfar);
    if (active) {
        p.ctx.originFilter(near);
        st.raysFiltered += near ? uint64_t(active) : 0;
        rtcOccluded16(p.valid, accel.rtcScene(), &p.ctx.rtc, &p.ray);
        if (!p.nearIds.empty()) decideNearField(p, st);
    }
    const int lit = addRound(sums, p.batch.weight, p.valid, p.ray.tfar);
    st.raysOccluded += uint64_t(active - lit);
    st.raysTraced += uint64_t(active);
}

// Rounds of 16 samples until the pixel's 95% half-width is at most the target (checked from
// kMinAdaptiveSpp on), or its budget is spent; with a fixed count, exactly that many (rounded up
// to whole rounds).
PixelResult samplePixel(const Accel& accel, const AreaLight& light, const AreaPixel& px,
                        const AreaSampling& sampling, uint32_t pixelSeed, const glm::vec3& org,
                        uint32_t originId, float tangentCos, PacketState& p, AreaShadowStats& st) {
    for (int k = 0; k < 16; ++k) {
        p.ray.org_x[k] = org.x;
        p.ray.org_y[k] = org.y;
        p.ray.org_z[k] = org.z;
        // Beyond the near field where the pass decides it (decideNearField).
        p.ray.tnear[k] = p.nearTriangles.empty() ? 0.0f : p.nearTnear;
        p.ray.time[k] = 0.0f;
        p.ray.mask[k] = 0xFFFFFFFFu;
        p.ray.flags[k] = 0;
        p.ray.id[k] = originId;  // the filter skips this triangle
    }
    const ReplicaSeeds seeds = replicaSeeds(pixelSeed);
    const int maxSpp = sampling.fixedSpp > 0 ? sampling.fixedSpp : sampling.maxSpp;
    ReplicaSums sums;
    PixelResult r;
    std::vector<double>& history = p.history;
    p.history.clear();
    p.halfWidths.clear();
    const bool adaptive = sampling.fixedSpp == 0;
    for (uint32_t first = 0;; first += kPointsPerRound) {
        traceRound(accel, light, px, seeds, first, tangentCos, p, sums, st);
        r.samples += 16;
        const int round = r.samples / 16;
        // A fixed count needs the estimate only where the cost curve reads it, and at the end.
        if (!adaptive && r.samples < maxSpp && !onCostCurve(round)) {
            p.halfWidths.push_back(p.halfWidths.empty() ? 1.0f : p.halfWidths.back());
            continue;
        }
        r.est = replicaEstimate(sums, adaptive);
        p.halfWidths.push_back(float(kIntervalQuantile95 * r.est.stderr_));
        r.agreeing = sums.agreeing();
        r.threshold = r.agreeing ? std::max(sampling.targetError, sampling.agreementTarget)
                                 : sampling.targetError;
        if (!adaptive) {
            if (r.samples >= maxSpp) break;
            continue;
        }
        // The stopping rule reads the decision half only (area_shadow.h: the stated estimate is
        // independent of it). Four replicas estimate the spread roughly: a pixel should not stop
        // on a lucky low estimate, which would leave the stated half-width above the target, so
        // the decision spread of half as many samples, scaled by RQMC's N^-0.75 for edges, bounds
        // it from below. The prior's floor is no estimate and needs no guard.
        history.push_back(r.est.stderrDecision);
        const int half = round / 2;
        const double decisionSe = std::max(
            r.est.stderrDecision, half >= 1 ? history[size_t(half - 1)] * guardScale(round) : 0.0);
        // The prior: where every sample agrees, the pixel's own (what it states); otherwise the
        // decision half's.
        r.decisionHalfWidth = std::max(
            kAdaptiveQuantile95 * decisionSe,
            r.agreeing
                ? kIntervalQuantile95 * r.est.stderrPrior
                : std::max(kIntervalQuantile95 * r.est.stderrPrior, r.est.decisionPriorHalfWidth));
        if (r.samples >= maxSpp) break;
        // The rule is read about eight times per doubling of the samples, not after every
        // packet: fewer looks waste fewer samples past the point the decision would pick anyway.
        // Where all samples agree the half-width is the prior's, a function of N alone: read
        // every packet.
        const bool look = r.agreeing || round % std::max(1, round / 8) == 0;
        if (r.samples >= kMinAdaptiveSpp && look && r.decisionHalfWidth <= r.threshold) break;
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
    AreaShadowPlanes out;
    std::vector<int> rounds;
    std::vector<float> perSampleVar, halfWidth;  // per slot
    std::vector<double> efficiency;              // per slot
    std::vector<CurveRow> curveRows;             // per tile row
    NearTarget target;                           // the light for near-field relevance

    void pixel(size_t s, int ty, PacketState& packet, AreaShadowStats& st);
    void reduceSlots(AreaShadowStats& total) const;
    void reduceCurve(AreaShadowStats& total) const;
};

// The part of the pixel's near field that segments to the light can reach (near_field.h): Embree
// starts the pixel's rays beyond the near field and decideNearField tests it.
void setNearField(const Accel& accel, const SurfaceBuffer& sb, size_t s, const NearTarget& target,
                  PacketState& packet) {
    const NearFields& f = sb.nearFields;
    packet.nearIds.clear();
    packet.nearTriangles.clear();
    if (accel.filters() && f.from(s) != f.to(s + 1)) {
        appendRelevant(f, f.from(s), f.to(s + 1), target, glm::dvec3(sb.lsRayOrigin(s)),
                       packet.nearIds, packet.nearTriangles);
        packet.nearTnear = f.tnear[s];
    }
}

// The light as near_field.h's relevance test sees it: points whose convex hull holds it.
NearTarget nearTarget(const AreaLight& light) {
    return light.kind->nearTarget(light);
}

void AreaRun::pixel(size_t s, int ty, PacketState& packet, AreaShadowStats& st) {
    const size_t px = sb.pixelOfSlot(s);
    if (px == SIZE_MAX || (out.onlySlots && !(*out.onlySlots)[s])) return;
    out.V[px] = out.stderr_[px] = out.spp[px] = out.cosine[px] = 0.0f;
    if (!sb.hit[s]) {
        ++st.skippedBackground;
        return;
    }
    const glm::vec3 p = sb.lsPoint(s), n = sb.lsNormal(s);
    out.cosine[px] = glm::dot(n, glm::normalize(light.lsCenter - p));
    const PixelTies ties{accel, sb, s, packet.facingCache, st.exactDecisions};
    switch (classifyAreaPixel(light, glm::dvec3(p), glm::dvec3(n), &ties)) {
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
    setNearField(accel, sb, s, target, packet);
    st.nearFieldPixels += !packet.nearIds.empty();
    const PixelResult r =
        samplePixel(accel, light, prepareAreaPixel(light, p, n), sampling,
                    areaPixelSeed(sampling.seed, stream, uint32_t(sb.fullImagePixel(px))),
                    sb.lsRayOrigin(s), sb.originId[s], sb.tangentCos[s], packet, st);
    out.V[px] = float(r.est.V);
    out.stderr_[px] = float(r.est.stderr_);
    out.spp[px] = float(r.samples);
    addToCurve(rounds, packet.halfWidths, out.V[px] > 0.0f && out.V[px] < 1.0f,
               curveRows[size_t(ty)]);
    const double hw = kIntervalQuantile95 * r.est.stderr_;
    st.samples += uint64_t(r.samples);
    st.sppMax = std::max<uint64_t>(st.sppMax, uint64_t(r.samples));
    st.pixelsReachedTarget += hw <= r.threshold;
    if (r.agreeing) {
        ++st.pixelsAgreeing;
        st.samplesAgreeing += uint64_t(r.samples);
    }
    // Unconverged: the budget ran out before the stopping rule was met. The stated half-width of
    // a pixel that stopped can still exceed the threshold (the stated half is an independent
    // estimate of the same spread): counted by pixelsReachedTarget, not marked.
    if (sampling.fixedSpp == 0 && r.decisionHalfWidth > r.threshold) {
        ++st.pixelsUnconverged;
        if (out.unconverged) out.unconverged[px] = 1.0f;
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
            total.uniformSpp = std::max(total.uniformSpp, uniformSppFor(v, total.worstHalfWidth));
    total.samplingEfficiency =
        total.pixelsSampled ? efficiencySum / double(total.pixelsSampled) : 1.0;
}

// The cost curve from the rows, in row order, and the run as it ended.
void AreaRun::reduceCurve(AreaShadowStats& total) const {
    const int roundsUsed = int((total.sppMax + 15) / 16);
    uint64_t penumbraPixels = 0;
    for (const CurveRow& row : curveRows) penumbraPixels += row.penumbraPixels;
    for (size_t c = 0; c < rounds.size() && rounds[c] <= roundsUsed && total.pixelsSampled; ++c) {
        CostPoint point{rounds[c], 0, 0.0, std::nullopt};
        double penumbraSum = 0.0;
        for (const CurveRow& row : curveRows) {
            point.samples += row.samples[c];
            point.meanHalfWidth += row.halfWidthSum[c];
            penumbraSum += row.penumbraHalfWidthSum[c];
        }
        point.meanHalfWidth /= double(total.pixelsSampled);
        if (penumbraPixels) point.penumbraMeanHalfWidth = penumbraSum / double(penumbraPixels);
        total.costCurve.push_back(point);
    }
    if (total.pixelsSampled &&
        (total.costCurve.empty() || total.costCurve.back().rounds < roundsUsed)) {
        double sum = 0.0, penumbraSum = 0.0;
        for (size_t s = 0; s < halfWidth.size(); ++s) {
            sum += halfWidth[s];
            const size_t px = sb.pixelOfSlot(s);
            if (px != SIZE_MAX && out.V[px] > 0.0f && out.V[px] < 1.0f) penumbraSum += halfWidth[s];
        }
        total.costCurve.push_back(
            {roundsUsed, total.samples, sum / double(total.pixelsSampled),
             penumbraPixels ? std::optional(penumbraSum / double(penumbraPixels)) : std::nullopt});
    }
}

// The run's settings and the sampler's description, as oracle.json states them.
AreaShadowStats settingsOf(const AreaLight& light, const AreaSampling& sampling) {
    AreaShadowStats s;
    s.sampling = light.kind->sampling();
    if (sampling.fixedSpp <= 0) {
        s.targetError = sampling.targetError;
        s.agreementTarget = sampling.agreementTarget;
    }
    s.maxSpp = sampling.fixedSpp > 0 ? sampling.fixedSpp : sampling.maxSpp;
    return s;
}

}  // namespace

AreaShadowStats traceAreaShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const AreaLight& light, const AreaSampling& sampling,
                                 uint32_t stream, const AreaShadowPlanes& out, Progress* progress) {
    auto t0 = std::chrono::steady_clock::now();
    const int maxSpp = sampling.fixedSpp > 0 ? sampling.fixedSpp : sampling.maxSpp;
    const std::vector<int> rounds = curveRounds((maxSpp + 15) / 16);
    AreaRun run{
        accel,
        sb,
        light,
        sampling,
        stream,
        out,
        rounds,
        std::vector<float>(sb.slotCount(), 0.0f),
        std::vector<float>(sb.slotCount(), 0.0f),
        std::vector<double>(sb.slotCount(), 0.0),
        std::vector<CurveRow>(size_t(sb.tilesY), {std::vector<uint64_t>(rounds.size(), 0),
                                                  std::vector<double>(rounds.size(), 0.0),
                                                  std::vector<double>(rounds.size(), 0.0), 0}),
        nearTarget(light)};
    tbb::combinable<AreaShadowStats> partial;
    // A chunk of rows: the thread's counts and the chunk's packet state.
    struct Scratch {
        AreaShadowStats& st;
        PacketState packet;
    };
    const auto makeScratch = [&] {
        Scratch c{partial.local(), {}};
        c.packet.ctx = accel.shadowContext(/*coherent=*/true);
        return c;
    };
    forEachTileRow(
        sb.tilesY, makeScratch,
        [&](int ty, Scratch& c) {
            for (size_t tile = size_t(ty) * size_t(sb.tilesX);
                 tile < size_t(ty + 1) * size_t(sb.tilesX); ++tile) {
                uint64_t pixels = 0;
                for (size_t s = tile * 16; s < tile * 16 + 16; ++s) {
                    run.pixel(s, ty, c.packet, c.st);
                    pixels += sb.pixelOfSlot(s) != SIZE_MAX;
                }
                // Per tile, not per row of tiles: a row of a wide image at a tight target can
                // take seconds, and a caller's cancel (Ctrl-C in Python) waits for the next report.
                if (progress) progress->advance(pixels);
            }
        },
        [](Scratch& c, uint64_t alphaTestsRun) { c.st.alphaTests += alphaTestsRun; });
    AreaShadowStats total = settingsOf(light, sampling);
    partial.combine_each([&](const AreaShadowStats& s) { combineStats(total, s); });
    run.reduceSlots(total);
    run.reduceCurve(total);
    total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return total;
}

}  // namespace so
