#include "oracle/replica_estimate.h"

#include <algorithm>
#include <cmath>

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

int addRound(ReplicaSums& s, const float* weight, const int* valid, const float* tfar) {
    // Branch-free: a lane not traced adds exact zeros (the sums are never -0), so the sums are
    // bit for bit those of adding the traced lanes alone, in lane order.
    double w[16], wv[16];
    int lit = 0, traced = 0;
    for (int k = 0; k < 16; ++k) {
        const bool on = valid[k] != 0;
        const bool l = on && tfar[k] >= 0.0f;
        w[k] = on ? double(weight[k]) : 0.0;
        wv[k] = l ? w[k] : 0.0;
        lit += l ? 1 : 0;
        traced += on ? 1 : 0;
    }
    for (int k = 0; k < 16; ++k) {
        s.x[size_t(k / kPointsPerRound)] += wv[k];
        s.y[size_t(k / kPointsPerRound)] += w[k];
    }
    for (int k = 0; k < 16; ++k) {
        s.sw2 += w[k] * w[k];
        s.sw2v += w[k] * wv[k];
    }
    int tracedDecision = 0;
    for (int k = 0; k < kDecisionReplicas * kPointsPerRound; ++k) tracedDecision += valid[k] != 0;
    s.lit += uint64_t(lit);
    s.nonZero += uint64_t(traced);
    s.nonZeroDecision += uint64_t(tracedDecision);
    return lit;
}

RatioEstimate replicaEstimate(const ReplicaSums& s, bool split) {
    double x = 0.0, y = 0.0;
    for (int j = 0; j < kReplicas; ++j) x += s.x[size_t(j)], y += s.y[size_t(j)];
    RatioEstimate e;
    if (s.nonZero == 0 || !(y > 0.0)) {
        e.stderr_ = 0.5;  // nothing measured: as uncertain as a [0, 1] quantity can be
        e.stderrDecision = 0.5;
        return e;
    }
    e.V = x / y;
    // Delta method over the replicas, which are independent: the ratio's variance from the
    // spread of the residuals r_j = x_j - V y_j (they sum to 0), K - 1 degrees of freedom.
    std::array<double, kReplicas> r;
    for (int j = 0; j < kReplicas; ++j) r[size_t(j)] = s.x[size_t(j)] - e.V * s.y[size_t(j)];
    const double yMean = y / kReplicas;
    // The standard error of V from a per-replica variance estimate.
    const auto seOf = [&](double replicaVariance) {
        return std::sqrt(replicaVariance / kReplicas) / yMean;
    };
    if (!split) {
        double ss = 0.0;
        for (double rj : r) ss += rj * rj;
        e.stderrSpread = seOf(ss / (kReplicas - 1.0));
    } else {
        // The sum of squares split in orthogonal parts, independent for normal replicas: within
        // the first half (3 dof), within the second (3), between the halves' means (1).
        double meanA = 0.0, meanB = 0.0;
        for (int j = 0; j < kReplicas; ++j) (j < kDecisionReplicas ? meanA : meanB) += r[size_t(j)];
        constexpr int kStatedReplicas = kReplicas - kDecisionReplicas;
        meanA /= kDecisionReplicas, meanB /= kStatedReplicas;
        double ssA = 0.0, ssB = 0.0;
        for (int j = 0; j < kReplicas; ++j) {
            const double d = r[size_t(j)] - (j < kDecisionReplicas ? meanA : meanB);
            (j < kDecisionReplicas ? ssA : ssB) += d * d;
        }
        const double ssBetween =
            kDecisionReplicas * meanA * meanA + kStatedReplicas * meanB * meanB;
        e.stderrDecision = seOf(ssA / (kDecisionReplicas - 1.0));
        // Where every sample of the decision half agrees (no sample of its four replicas met a
        // thin occluder that the others met, or the reverse), the prior's floor on its samples
        // alone: the rule must not take the half's spread of 0 for certainty. (Sums of all-lit
        // samples are x = y bit for bit.)
        double xA = 0.0, yA = 0.0;
        for (int j = 0; j < kDecisionReplicas; ++j) xA += s.x[size_t(j)], yA += s.y[size_t(j)];
        const bool halfAgrees = xA == 0.0 || xA == yA;
        if (!halfAgrees) {
            e.decisionPriorHalfWidth = 0.0;
        } else if (s.nonZeroDecision > 0 && yA > 0.0) {
            const Prior prA = agrestiCoull(yA, xA, s.nonZeroDecision);
            e.decisionPriorHalfWidth = kZ * std::sqrt(prA.share) / prA.W;
        } else {
            e.decisionPriorHalfWidth = 1.0;
        }
        e.stderrSpread =
            seOf((ssB + ssBetween) / kAdaptiveDof) * kAdaptiveQuantile95 / kIntervalQuantile95;
    }
    // The prior's share of the iid estimate: it keeps "all samples agree" from meaning "certain",
    // and dominates only where the replicas barely differ.
    const Prior pr = agrestiCoull(y, x, s.nonZero);
    const double sePrior = std::sqrt(pr.share) / pr.W;
    // Stated as a standard error for the t quantile: half-width max(t se, z sePrior).
    e.stderrPrior = kZ * sePrior / kIntervalQuantile95;
    e.stderr_ = std::max(e.stderrSpread, e.stderrPrior);
    return e;
}

}  // namespace so
