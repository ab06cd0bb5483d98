// Error of a technique's shadows against the oracle, split by artifact (docs/metrics.md: the names
// and definitions are a public contract). Pure functions of two images, so they are tested on
// synthetic pairs with known answers (tests/metrics_test.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "raster_compare/compare/artifacts.h"

namespace so {

struct MetricOptions {
    int boundaryRadius = 2;  // r: pixels from an oracle shadow boundary
    double contactThreshold =
        0.0;  // occluder distance below which a shadow is "at contact" (world units)
    bool filteredTechnique = false;  // light bleeding is only measured for filtered techniques
};

struct BoundaryDisplacement {
    double mean = 0.0, p95 = 0.0, max = 0.0;
    size_t pixels = 0;  // boundary pixels measured (both images)
};

struct LightMetrics {
    size_t counted = 0;
    size_t excludedBackground = 0, excludedDifferentSurface = 0, excludedFacingAway = 0;
    double mae = 0.0, rmse = 0.0, maxAbs = 0.0;
    double falseShadowRate = 0.0, falseLitRate = 0.0;
    double acneRate = 0.0;
    std::optional<double> peterPanningRate, lightLeakDistance;  // need the oracle's occ_dist
    BoundaryDisplacement boundaryDisplacement;
    double aliasingRate = 0.0;
    std::optional<double> lightBleedingRate;          // filtered techniques only
    std::optional<double> penumbraMae, penumbraBias;  // area lights only (oracle stderr present)
    // With the raster's NAME.aliasing_pred: its mean over counted pixels, and the Pearson
    // correlation of its log with the boundary displacement at the raster's boundary pixels.
    std::optional<double> predictedAliasingMean, aliasingCorrelation;
    nlohmann::json toJson() const;
};

// Per-pixel error classes, for the error EXRs and the report's maps: 1 where the pixel counts
// towards that class's metric as an error, else 0; `error` is the pixel's error (see mae).
struct ErrorMaps {
    std::array<std::vector<float>, kArtifactCount> classes;  // by Artifact
    std::vector<float> error;
    std::vector<float>& of(Artifact a) { return classes[size_t(a)]; }
    const std::vector<float>& of(Artifact a) const { return classes[size_t(a)]; }
};

// What a technique's shadows cost, beside its metrics in every row of metrics.json.
struct TechniqueCost {
    double shadowMapMs = 0.0, visibilityMs = 0.0, frameMs = 0.0;  // medians over timed frames
    double oracleSeconds = 0.0;  // what the ground truth of this light cost
    nlohmann::json toJson() const;
};

// One technique against the oracle for one light: a row of metrics.json.
struct LightComparison {
    std::string light;
    LightMetrics metrics;
    TechniqueCost cost;
    ErrorMaps maps;
    nlohmann::json toJson() const;  // metrics with "cost"
};

// `oracle` and `raster` follow docs/exr-channels.md; `light` names the light. `maps`, if given,
// receives the per-pixel classes.
LightMetrics computeLightMetrics(const ChannelImage& oracle, const ChannelImage& raster,
                                 const std::string& light, const MetricOptions& options,
                                 ErrorMaps* maps = nullptr);

}  // namespace so
