// What a shadow pass reports about itself: the hard pass (hard_shadow.h) and the sampled pass
// (area_shadow.h) return these, oracle.json stores them per light (oracle_stats.h, docs/oracle.md)
// and trace-merge adds them up. Each counter is listed once, in its struct's fields() table
// (stat_fields.h). Values that follow from others (rays per second, spp mean) are methods, so the
// JSON cannot disagree with itself.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "oracle/exact_penumbra.h"
#include "oracle/stat_fields.h"

namespace so {

// One shadow ray per pixel (hard_shadow.h): hard lights, area lights without "penumbra" (one ray
// to the centre), and the contact rays of sampled area lights.
struct HardShadowStats {
    uint64_t raysTraced = 0, raysOccluded = 0;
    uint64_t skippedBackground = 0, skippedAttached = 0;
    std::optional<uint64_t> skippedOutsideCone;  // spot lights only
    std::optional<uint64_t> skippedBehindLight;  // one-sided lights (rect, disk) only
    uint64_t closestHitQueries = 0;              // only with the contact effect
    uint64_t exactDecisions = 0;  // pixels a float tie left to exact arithmetic (exact_facing.h)
    uint64_t alphaTests = 0;      // candidate hits on alpha-tested geometry, tested
    // Rays in packets that ran the origin-triangle filter: those holding a ray within its
    // triangle's tangency bound (offset.h, accel.h).
    uint64_t raysFiltered = 0;
    // The near field (near_field.h): pixels with near-field triangles their segment can reach, and
    // the rays those then blocked.
    uint64_t nearFieldPixels = 0, nearFieldOccluded = 0;
    double seconds = 0.0;

    double raysPerSecond() const;
    static std::span<const StatField<HardShadowStats>> fields();
};

// One point of a light's cost curve: had every pixel stopped after at most `rounds` packets, the
// samples spent over all pixels and the mean stated 95% half-width (pixels that stopped earlier
// keep theirs).
struct CostPoint {
    int rounds = 0;
    uint64_t samples = 0;
    double meanHalfWidth = 0.0;
    // The same mean over the penumbra's pixels only (those ending with 0 < V < 1: their samples
    // disagreed), what a soft-shadow technique's penumbra error compares with; none without any.
    std::optional<double> penumbraMeanHalfWidth;
};

// The sampled pass of an area light with "penumbra" (area_shadow.h).
struct AreaShadowStats {
    std::string sampling;  // how a sample picks its point on the light
    // The settings the pass ran with.
    std::optional<double> targetError;  // none with a fixed spp
    // Adaptive: pixels whose samples all agree stop at max(targetError, this) (area_shadow.h).
    std::optional<double> agreementTarget;
    int maxSpp = 0;  // the fixed spp, or the adaptive cap

    uint64_t raysTraced = 0, raysOccluded = 0;
    uint64_t skippedBackground = 0, skippedBelowHorizon = 0, skippedBehindLight = 0,
             skippedInsideLight = 0;
    uint64_t exactDecisions = 0;  // pixels whose horizon or emitter side was decided exactly
    uint64_t alphaTests = 0;      // candidate hits on alpha-tested geometry, tested
    uint64_t raysFiltered = 0;    // rays in packets that ran the origin-triangle filter
    // The near field (near_field.h): pixels with near-field triangles their segments to the light
    // can reach, rays Embree left lit that were then tested against them in double, and those
    // they blocked.
    uint64_t nearFieldPixels = 0, nearFieldRays = 0, nearFieldOccluded = 0;
    uint64_t samples = 0, pixelsSampled = 0, sppMax = 0;
    // Pixels where the light is above the horizon only by a sliver no sample found: reported as
    // V = 0 with the widest interval, and left out of worstHalfWidth (they carry no estimate).
    uint64_t pixelsWithoutUsableSamples = 0;
    // Pixels whose half-width reached their threshold (oracle.json gives the share).
    uint64_t pixelsReachedTarget = 0;
    uint64_t pixelsUnconverged = 0;  // adaptive: budget spent, target missed (NAME.unconverged)
    // Pixels whose samples all agreed (lit, or umbra) and the samples they took: the part of the
    // cost the agreement target sets.
    uint64_t pixelsAgreeing = 0, samplesAgreeing = 0;
    double worstHalfWidth = 0.0;  // the largest half-width over sampled pixels
    double uniformSpp = 0.0;      // a uniform run reaching worstHalfWidth everywhere
    double seconds = 0.0;
    double samplingEfficiency = 1.0;  // mean over pixels of Kish's n_eff / n for the weights
    // What accuracy cost as the run went; seconds are pro rata. About two points per doubling of
    // the packets, up to the most any pixel used.
    std::vector<CostPoint> costCurve;
    // With --penumbra exact or both: the exact pass (oracle.json "exact_penumbra").
    std::optional<ExactPenumbraStats> exact;

    uint64_t samplesWithoutRay() const { return samples - raysTraced; }
    double shareReachedTarget() const;
    // Adaptive runs: the seconds a run with `target` would take. The agreeing pixels' share of the
    // samples scales as their threshold's inverse (the prior's half-width goes as 1 / N); the
    // rest by the slope of the cost curve while every pixel was still sampling (the mean
    // half-width goes as samples^slope). None without enough of the curve.
    std::optional<double> predictedSeconds(double target) const;
    std::optional<double> costSlope() const;
    double sppMean() const;
    double uniformSamples() const;  // uniformSpp over the pixels sampled
    double uniformRays() const;     // uniformSamples at this run's rays per sample
    double raysPerSecond() const;
    // The counters (not the settings, the means or the curve). pixelsReachedTarget has no key:
    // oracle.json writes it as share_reached_target.
    static std::span<const StatField<AreaShadowStats>> fields();
};

}  // namespace so
