// The statistics of the area pass's estimator (area_shadow.h samples; docs/oracle.md): per pixel,
// the replicas' running sums, the ratio estimate V = sum w v / sum w and its standard error, from
// the delta method over the replicas and at least an Agresti-Coull-style prior's share, and for
// adaptive runs the split of the replicas into a decision half and a stated half. Pure arithmetic
// on the sums: no rays, no Embree.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "core/channels.h"

namespace so {

// Two-sided 95% normal quantile (the prior, and the verifier's independent reference samples).
inline constexpr double kZ95 = 1.959963984540054;

// Randomized QMC: every pixel's samples come from kReplicas independently Owen-scrambled Sobol
// sequences, two points of each per 16-ray packet. The replicas' estimates are independent, so
// their spread gives an honest standard error (the points within one are not independent).
inline constexpr int kReplicas = 8;
inline constexpr int kPointsPerRound = 16 / kReplicas;
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

// Adds a traced round to the sums: lane k (replica k / kPointsPerRound) where valid[k] != 0,
// with weight[k] > 0, lit where tfar[k] >= 0 (Embree sets it to -inf on a hit). Returns the lanes
// that were lit.
int addRound(ReplicaSums& s, const float* weight, const int* valid, const float* tfar);

}  // namespace so
