// What a run of the oracle reports about itself (docs/oracle.md): typed, filled by runOracle, and
// turned into JSON only where oracle.json is written (toJson) or read back (oracleStatsFromJson).
// Values that follow from others (rays per second, spp mean, the verify totals) are methods, so
// the JSON cannot disagree with itself.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "core/scene.h"
#include "oracle/area_shadow.h"
#include "oracle/exact_penumbra.h"
#include "oracle/verify.h"

namespace so {

// The hard-shadow pass of one light: hard lights, area lights without "penumbra" (one ray to the
// centre), and the contact rays of sampled area lights.
struct OracleHardStats {
    uint64_t raysTraced = 0, raysOccluded = 0;
    uint64_t skippedBackground = 0, skippedAttached = 0;
    std::optional<uint64_t> skippedOutsideCone;  // spot lights only
    std::optional<uint64_t> skippedBehindLight;  // one-sided lights (rect, disk) only
    uint64_t closestHitQueries = 0;              // only with the contact effect
    uint64_t exactDecisions = 0;  // pixels a float tie left to exact arithmetic (exact_facing.h)
    uint64_t alphaTests = 0;      // candidate hits on alpha-tested geometry, tested
    double seconds = 0.0;
    double raysPerSecond() const;
};

// The sampled pass of an area light with "penumbra".
struct OracleAreaStats {
    std::string sampling;  // how a sample picks its point on the light
    uint64_t raysTraced = 0, raysOccluded = 0;
    uint64_t skippedBackground = 0, skippedBelowHorizon = 0, skippedBehindLight = 0,
             skippedInsideLight = 0;
    uint64_t exactDecisions = 0;  // pixels a float tie left to exact arithmetic (exact_facing.h)
    uint64_t alphaTests = 0;      // candidate hits on alpha-tested geometry, tested
    uint64_t samples = 0, pixelsSampled = 0, pixelsWithoutUsableSamples = 0, sppMax = 0;
    std::optional<double> targetError;  // none with a fixed spp
    // Adaptive: pixels whose samples all agree stop at max(targetError, this) (area_shadow.h).
    std::optional<double> agreementTarget;
    int maxSpp = 0;  // the fixed spp, or the adaptive cap
    double shareReachedTarget = 1.0;
    uint64_t pixelsUnconverged = 0;  // adaptive: budget spent, target missed (NAME.unconverged)
    // Pixels whose samples all agreed (lit, or umbra) and the samples they took.
    uint64_t pixelsAgreeing = 0, samplesAgreeing = 0;
    double worstHalfWidth = 0.0;
    double uniformSpp = 0.0;  // a uniform run reaching worstHalfWidth everywhere
    double samplingEfficiency = 1.0;
    double seconds = 0.0;
    // What accuracy cost as the run went (area_shadow.h CostPoint); seconds are pro rata.
    std::vector<CostPoint> costCurve;
    // With --penumbra exact or both: the exact pass (oracle.json "exact_penumbra").
    std::optional<ExactPenumbraStats> exact;

    uint64_t samplesWithoutRay() const { return samples - raysTraced; }
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
};

struct OracleLightStats {
    std::string name;
    LightType type = LightType::Point;
    std::string method;                   // how the light was traced, for people
    std::optional<OracleAreaStats> area;  // sampled (penumbra) area lights
    // Every other light; for a sampled area light, its contact rays (with "contact" only).
    std::optional<OracleHardStats> hard;

    bool sampled() const { return area.has_value(); }
    // oracle.json's lights[i].seconds: the sampled pass for sampled lights, else the hard pass.
    double seconds() const;
};

struct OracleFrameStats {
    glm::dvec3 wsCenter{0.0};
    int scaleExponent = 0;
};

struct OracleOffsetStats {
    std::string method;
    bool skipsOriginTriangle = true;
    double maxBlindDistance = 0.0;  // world units
    double maxBlindDistanceRelative = 0.0;
};

struct OracleEmbreeStats {
    std::string version, sceneFlags, buildQuality;
};

// What --verify found (verify.h).
struct OracleVerifyStats {
    VerifyOptions options;
    double wsToleranceAbs = 0.0;            // Verifier::kTolAbs in world units
    double tolerancePerUnitDistance = 0.0;  // Verifier::kTolPerT
    double buildSeconds = 0.0;              // the reference BVH
    std::vector<LightVerification> lights;  // one per light, in scene order

    uint64_t disagreements() const { return disagreementCount(lights); }
    double seconds() const;  // buildSeconds plus every light's
};

struct OracleStats {
    int width = 0, height = 0;
    int threads = 0;
    double buildBvhSeconds = 0.0, primarySeconds = 0.0, shadowSeconds = 0.0;
    uint64_t shadowRays = 0, closestHitQueries = 0;
    uint64_t primaryAlphaTests = 0, shadowAlphaTests = 0;  // alpha tests (core/alpha_mask.h)
    std::vector<std::string> effects;
    uint32_t seed = 0;
    std::vector<OracleLightStats> lights;  // in scene order
    OracleFrameStats frame;
    OracleOffsetStats offsetPolicy;
    OracleEmbreeStats embree;
    std::string tbbVersion;
    std::optional<OracleVerifyStats> verify;  // with --verify only

    double shadowRaysPerSecond() const;
    bool verified() const { return verify.has_value(); }  // --verify ran (whatever it found)
    uint64_t disagreements() const { return verify ? verify->disagreements() : 0; }
};

// One band's stats (`trace --tile`) and what merging needs beyond them.
struct TileStats {
    OracleStats stats;
    // Per light, in scene order: the pixels of a sampled light whose V ended strictly between 0
    // and 1 (the penumbra the cost curve's penumbra mean averages over); 0 for other lights.
    std::vector<uint64_t> penumbraPixels;
};

// The whole image's stats from its bands' (trace-merge; docs/oracle.md, "Tiles"): counts,
// samples, rays and seconds are sums, maxima are maxima, means are re-weighted by what they
// average over, and the setup (effects, seed, frame, libraries) is the first band's. The bands
// must come from the same scene and options, in any order. uniformSpp is the bands' largest: only
// the per-pixel variances give the whole image's (the caller recomputes it from the image). No
// bands, or bands whose lights differ, are std::invalid_argument.
OracleStats mergeTileStats(const std::vector<TileStats>& tiles, int width, int height);

// Exactly the run-dependent part of oracle.json (docs/oracle.md).
nlohmann::json toJson(const OracleStats& stats);
// The inverse of toJson: toJson(oracleStatsFromJson(toJson(s), f)) == toJson(s). Throws InputError
// naming `file` and the field on a missing or mistyped field. A null where a number is expected
// reads as NaN (nlohmann writes non-finite numbers as null); derived values are not read.
OracleStats oracleStatsFromJson(const nlohmann::json& json, const std::string& file);

}  // namespace so
