#include "oracle/pass_stats.h"

#include <algorithm>
#include <cmath>

#include "oracle/area_shadow.h"

namespace so {

std::span<const StatField<HardShadowStats>> HardShadowStats::fields() {
    using S = HardShadowStats;
    static constexpr StatField<S> kFields[] = {
        {"rays_traced", &S::raysTraced},
        {"rays_occluded", &S::raysOccluded},
        {"rays_skipped.background", &S::skippedBackground},
        {"rays_skipped.attached", &S::skippedAttached},
        {"rays_skipped.outside_cone", &S::skippedOutsideCone},
        {"rays_skipped.behind_light", &S::skippedBehindLight},
        {"closest_hit_queries", &S::closestHitQueries},
        {"exact_decisions", &S::exactDecisions},
        {"alpha_tests", &S::alphaTests},
        {"rays_filtered", &S::raysFiltered},
        {"near_field.pixels", &S::nearFieldPixels},
        {"near_field.rays_occluded", &S::nearFieldOccluded},
        {"seconds", &S::seconds},
    };
    return kFields;
}

std::span<const StatField<AreaShadowStats>> AreaShadowStats::fields() {
    using S = AreaShadowStats;
    static constexpr StatField<S> kFields[] = {
        {"rays_traced", &S::raysTraced},
        {"rays_occluded", &S::raysOccluded},
        {"rays_skipped.background", &S::skippedBackground},
        {"rays_skipped.below_horizon", &S::skippedBelowHorizon},
        {"rays_skipped.behind_light", &S::skippedBehindLight},
        {"rays_skipped.inside_light", &S::skippedInsideLight},
        {"exact_decisions", &S::exactDecisions},
        {"alpha_tests", &S::alphaTests},
        {"rays_filtered", &S::raysFiltered},
        {"near_field.pixels", &S::nearFieldPixels},
        {"near_field.rays_tested", &S::nearFieldRays},
        {"near_field.rays_occluded", &S::nearFieldOccluded},
        {"samples", &S::samples},
        {"pixels_sampled", &S::pixelsSampled},
        {"pixels_without_usable_samples", &S::pixelsWithoutUsableSamples},
        {"spp_max", &S::sppMax, Combine::Max},
        {nullptr, &S::pixelsReachedTarget},  // written as share_reached_target
        {"pixels_unconverged", &S::pixelsUnconverged},
        {"pixels_agreeing", &S::pixelsAgreeing},
        {"samples_agreeing", &S::samplesAgreeing},
        {"worst_half_width", &S::worstHalfWidth, Combine::Max},
        // A band's own; trace-merge recomputes the whole image's from the per-pixel variances.
        {"uniform_equivalent.spp", &S::uniformSpp, Combine::Max},
        {"seconds", &S::seconds},
    };
    return kFields;
}

double HardShadowStats::raysPerSecond() const {
    return seconds > 0 ? double(raysTraced) / seconds : 0.0;
}

double AreaShadowStats::shareReachedTarget() const {
    return pixelsSampled ? double(pixelsReachedTarget) / double(pixelsSampled) : 1.0;
}

std::optional<double> AreaShadowStats::costSlope() const {
    // The points where no pixel had stopped: samples = 16 x packets x pixels.
    const CostPoint* first = nullptr;
    const CostPoint* last = nullptr;
    for (const CostPoint& p : costCurve) {
        if (p.samples != 16 * uint64_t(p.rounds) * pixelsSampled) break;
        if (p.rounds * 16 < kMinAdaptiveSpp || !(p.meanHalfWidth > 0.0)) continue;
        if (!first) first = &p;
        last = &p;
    }
    if (!first || last == first) return std::nullopt;
    return std::log(last->meanHalfWidth / first->meanHalfWidth) /
           std::log(double(last->samples) / double(first->samples));
}

std::optional<double> AreaShadowStats::predictedSeconds(double target) const {
    const std::optional<double> slope = costSlope();
    if (!targetError || !slope || !(*slope < 0.0) || !(target > 0.0) || samples == 0)
        return std::nullopt;
    const double agree = agreementTarget.value_or(0.0);
    const double agreeShare = double(samplesAgreeing) / double(samples);
    const double agreeScale = std::max(*targetError, agree) / std::max(target, agree);
    return seconds * (agreeShare * agreeScale +
                      (1.0 - agreeShare) * std::pow(target / *targetError, 1.0 / *slope));
}

double AreaShadowStats::sppMean() const {
    return pixelsSampled ? double(samples) / double(pixelsSampled) : 0.0;
}

double AreaShadowStats::uniformSamples() const {
    return uniformSpp * double(pixelsSampled);
}

double AreaShadowStats::uniformRays() const {
    const double raysPerSample = samples ? double(raysTraced) / double(samples) : 0.0;
    return uniformSamples() * raysPerSample;
}

double AreaShadowStats::raysPerSecond() const {
    return seconds > 0 ? double(raysTraced) / seconds : 0.0;
}

}  // namespace so
