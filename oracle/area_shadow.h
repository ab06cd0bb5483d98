// Penumbrae by sampling: per pixel, packets of 16 shadow rays towards points on the light from 8
// independently Owen-scrambled Sobol sequences (randomized QMC: two points of each replica per
// packet), until the pixel's 95% interval is narrow enough (docs/oracle.md).
//
// The estimate is V = sum w v / sum w (area_light.h) over all samples. Its interval is
// V +- kIntervalQuantile95 * stderr, stderr from the delta method over the replicas (independent,
// so the spread is honest: 7 degrees of freedom, Student-t quantile), at least an
// Agresti-Coull-style prior's share (1.92 pseudo-samples lit and 1.92 shadowed at the mean weight)
// so that a pixel whose samples all agree is not declared certain.
//
// Stopping rule (adaptive): after each packet, from kMinAdaptiveSpp samples on, stop when the
// half-width predicted from the decision half of the replicas (kDecisionReplicas below) <= the
// pixel's threshold, or the pixel has max_spp samples; the stated interval comes from the other
// half and the contrast between the halves, which the decision never reads, so stopping cannot
// select it low (docs/oracle.md, "Stopping rule"). The threshold is the target error, or where
// every sample so far agrees (all lit, or all shadowed) max(target error, agreement target): there
// only the prior sets the half-width, about 2.7 / N, and what it bounds is the share of the light
// an occluder (or a gap) that no sample met may have, which more samples shrink only as 1 / N.
// With a fixed count (--spp N), exactly N samples, rounded up to whole packets, and all replicas'
// spread stated.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/channels.h"
#include "core/trace_option_table.h"

#include "oracle/accel.h"
#include "oracle/area_light.h"
#include "oracle/pass_stats.h"
#include "oracle/surface_buffer.h"

namespace so {

class Progress;

// Two-sided 95% normal quantile (the prior, and the verifier's independent reference samples).
inline constexpr double kZ95 = 1.959963984540054;

// Randomized QMC: every pixel's samples come from kReplicas independently Owen-scrambled Sobol
// sequences, two points of each per 16-ray packet. The replicas' estimates are independent, so
// their spread gives an honest standard error (the points within one are not independent).
inline constexpr int kReplicas = 8;
inline constexpr int kPointsPerRound = 16 / kReplicas;
// Adaptive runs check the stopping rule from this many samples on (4 points per replica).
inline constexpr int kMinAdaptiveSpp = 64;
// Every interval the oracle states is V +- kIntervalQuantile95 * stderr: the two-sided 95%
// Student-t quantile for kReplicas - 1 = 7 degrees of freedom.
inline constexpr double kIntervalQuantile95 = channels::kStdErrQuantile95;

// The samples a uniform run would need at a pixel of per-sample variance `perSampleVariance` (its
// stderr^2 * spp) to bring its 95% half-width down to `halfWidth`: the oracle's uniform
// equivalent (oracle.json uniform_equivalent), taken over pixels by their maximum, and the same
// after trace-merge.
inline double uniformSppFor(float perSampleVariance, double halfWidth) {
    return std::ceil(kIntervalQuantile95 * kIntervalQuantile95 * double(perSampleVariance) /
                     (halfWidth * halfWidth));
}
static_assert(kReplicas == 8, "kIntervalQuantile95 is the t quantile for 7 degrees of freedom");

// Adaptive runs split the replicas' spread in two independent parts (docs/oracle.md, "Stopping
// rule"): the first half's spread within itself (3 degrees of freedom) decides when a pixel stops
// and is never stated; the second half's spread within itself and the contrast between the halves
// (4 degrees of freedom) give the stated interval, V +- kAdaptiveQuantile95 * se. Under the
// replicas' normal model the stopping decision is independent of that estimate and of V, so
// stopping cannot select it low. Fixed counts have no stopping and state all 7.
inline constexpr int kDecisionReplicas = kReplicas / 2;
inline constexpr int kAdaptiveDof = kReplicas - kDecisionReplicas;
// The two-sided 95% Student-t quantile for kAdaptiveDof = 4 degrees of freedom.
inline constexpr double kAdaptiveQuantile95 = 2.7764451051977987;
static_assert(kAdaptiveDof == 4, "kAdaptiveQuantile95 is the t quantile for 4 degrees of freedom");

struct AreaSampling {
    double targetError = 0.01;  // 95% half-width
    // Pixels whose samples all agree stop at max(targetError, agreementTarget) (above).
    double agreementTarget = 0.01;
    int maxSpp = kDefaultMaxSpp;  // the trace option table's default
    int fixedSpp = 0;             // > 0: exactly this many samples per pixel, no adaptivity
    uint32_t seed = 0;
};

// Half-width and standard error of the estimate from the running sums (exposed for tests).
struct RatioEstimate {
    double V = 0.0, stderr_ = 0.0;
    // replicaEstimate only: the two parts stderr_ is the larger of, the replicas' spread and the
    // prior's floor (as a standard error for the t quantile).
    double stderrSpread = 0.0, stderrPrior = 0.0;
    // split only: the decision half's estimate of the standard error of V (3 degrees of freedom),
    // and the prior's floor on its samples alone as a 95% half-width, which the stopping rule
    // reads and nothing states.
    double stderrDecision = 0.0, decisionPriorHalfWidth = 0.0;
};
RatioEstimate ratioEstimate(double sw, double swv, double sw2, double sw2v, uint64_t nonZero);

// Running sums of one pixel: per replica sum w v (x) and sum w (y), and over all samples the sums
// the prior needs.
struct ReplicaSums {
    std::array<double, kReplicas> x{}, y{};
    double sw2 = 0.0, sw2v = 0.0;
    uint64_t nonZero = 0;  // samples with weight > 0
    // of those, the decision half's (replicas below kDecisionReplicas: area_shadow.h's split)
    uint64_t nonZeroDecision = 0;
    uint64_t lit = 0;  // of those, the ones that reached the light
    bool agreeing() const { return lit == 0 || lit == nonZero; }
};
// V = sum x / sum y; stderr from the delta method over the replicas, at least the prior's share
// (docs/oracle.md): V +- kIntervalQuantile95 * stderr is the pixel's 95% interval.
// split: adaptive runs' estimate (kAdaptiveDof above): the same V; stderrSpread from the stated
// half and the contrast between the halves, expressed as a standard error for kIntervalQuantile95
// (kAdaptiveQuantile95 / kIntervalQuantile95 times the estimate); stderrDecision set.
RatioEstimate replicaEstimate(const ReplicaSums& sums, bool split = false);

// The scrambling seeds of a pixel's replicas (from areaPixelSeed), one per lane of a round:
// lane k belongs to replica k / kPointsPerRound. Made once per pixel.
struct ReplicaSeeds {
    alignas(64) uint32_t u[16];  // the first dimension's scramble
    alignas(64) uint32_t v[16];  // the second's
};
ReplicaSeeds replicaSeeds(uint32_t pixelSeed);
// One round's packet: lanes 2j and 2j + 1 are points `first` and `first` + 1 of replica j's
// scrambled Sobol sequence, mapped onto the light (weight 0: no ray).
void sampleRound(const AreaLight& light, const AreaPixel& px, const ReplicaSeeds& seeds,
                 uint32_t first, AreaBatch& b);
// Adds a traced round to the sums: lane k (replica k / kPointsPerRound) where valid[k] != 0,
// with weight[k] > 0, lit where tfar[k] >= 0 (Embree sets it to -inf on a hit). Returns the lanes
// that were lit.
int addRound(ReplicaSums& s, const float* weight, const int* valid, const float* tfar);

// The seed of one pixel's sample sequence: `stream` separates lights, `pixel` is the row-major
// pixel index. The sequence depends on nothing else, so the image is the same at any thread count.
uint32_t areaPixelSeed(uint32_t seed, uint32_t stream, uint32_t pixel);

// Where the pass writes, one float per pixel of the surface buffer's image (or band) each.
struct AreaShadowPlanes {
    float* V = nullptr;
    float* stderr_ = nullptr;
    float* spp = nullptr;
    float* cosine = nullptr;       // towards the light's centre
    float* unconverged = nullptr;  // adaptive runs, else null: 1 where the budget ran out first
    // Where given, only the slots it marks are sampled and written (the pixels the exact pass
    // left, exact_penumbra.h); the others' planes are left as they are.
    const std::vector<uint8_t>* onlySlots = nullptr;
};

// `stream` separates the sample sequences of different lights. Runs in parallel inside the
// caller's task arena; the planes and the statistics are the same at any thread count.
AreaShadowStats traceAreaShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const AreaLight& light, const AreaSampling& sampling,
                                 uint32_t stream, const AreaShadowPlanes& out, Progress* progress);

}  // namespace so
