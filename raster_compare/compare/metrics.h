// Error of a technique's shadows against the oracle, split by artifact (docs/metrics.md: the names
// and definitions are a public contract). Pure functions of two images, so they are tested on
// synthetic pairs with known answers (tests/compare/metrics_test.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/compare_option_table.h"
#include "core/image.h"
#include "core/timing.h"
#include "core/work_counts.h"
#include "raster_compare/compare/artifacts.h"
#include "raster_compare/compare/penumbra_width.h"
#include "raster_compare/compare/sequence_metrics.h"
#include "raster_compare/compare/temporal.h"

namespace so {

// The schema_version of the metrics.json compare and sweep-merge write (docs/metrics.md): 9 gives
// the families that compare no depth no acne, and in a sequence classes ghosting apart (8 classed
// acne by its cause where the raster says what its depth comparison saw, and added
// screen_bleed_rate; 7 added cost.work; 6 added penumbra_spread_rate, and on area lights acne_rate
// and other_false_*_rate no longer count the pixels of a penumbra too wide or shifted).
inline constexpr int kMetricsSchemaVersion = 9;

struct MetricOptions {
    int boundaryRadius = kDefaultBoundaryRadius;  // r: pixels from an oracle shadow boundary
    double contactThreshold =
        0.0;  // occluder distance below which a shadow is "at contact" (world units)
    bool filteredTechnique = false;  // light bleeding is only measured for filtered techniques
    // Whether the technique compares depths at all (familyComparesDepth): acne is a surface
    // shadowed by its own depth, so a technique that compares none has no acne.
    bool comparesDepth = true;
    // In a sequence: 1 per pixel where the oracle's V changed by more than kLagJump within the
    // kLagFrames frames before (SequenceJudge::truthChanged). A wrong pixel there, away from the
    // oracle's boundary, is ghosting, not acne (docs/metrics.md#sequence). Null for a single frame:
    // no ghosting class, every other class as without it. Its size is the images' pixel count.
    const std::vector<uint8_t>* truthChanged = nullptr;
};

// Whether a technique family's shadows come from a depth comparison (docs/metrics.md, acne): not
// ray tracing (a ray finds its occluder or not), the shadow texture (an occluder's opacity
// projected) or the planar projections (casters flattened onto the receiver); every other family
// compares depths (shadow maps, virtual maps, their accumulation and blur, the lightmap's bake
// from a shadow map, the volumes' depth test against the camera's depth). By family name
// (TechniqueInfo::family), so that judging needs no raster code.
bool familyComparesDepth(const std::string& family);

// Distances in pixels between the two images' shadow boundaries (the V = 0.5 isoline), both ways.
struct BoundaryDisplacement {
    double mean = 0.0, p95 = 0.0, max = 0.0;
    size_t pixels = 0;  // boundary pixels measured (both images)
    // One image has a boundary and the other none (a shadow dropped or invented): each of its
    // boundary pixels is the image diagonal away, the worst value there is.
    bool missingBoundary = false;
};

struct LightMetrics {
    size_t counted = 0;
    size_t excludedBackground = 0, excludedDifferentSurface = 0, excludedFacingAway = 0;
    double mae = 0.0, rmse = 0.0, maxAbs = 0.0;
    double falseShadowRate = 0.0, falseLitRate = 0.0;
    // False shadow on fully lit pixels away from an oracle boundary; on area lights, only where
    // the technique's penumbra spreading past the oracle's does not explain it; where the raster
    // has its depth comparison's channels, only where that comparison shadowed the pixel by its
    // own surface.
    double acneRate = 0.0;
    // Where the raster has NAME.V_unfiltered (a screen-space pass after the comparison): false
    // shadow on fully lit pixels that the pixel's own comparison lit, over counted pixels.
    std::optional<double> screenBleedRate;
    std::optional<double> peterPanningRate, lightLeakDistance;  // need the oracle's occ_dist
    BoundaryDisplacement boundaryDisplacement;
    // Mean error within r pixels of an oracle boundary: credits a soft edge that the 0/1
    // threshold of the aliasing rate cannot see (none without an oracle boundary).
    std::optional<double> boundaryBandMae;
    // Wrong pixels (false shadow or false lit) that no named class explains, over counted pixels.
    double otherFalseShadowRate = 0.0, otherFalseLitRate = 0.0;
    std::optional<double> aliasingRate;       // hard lights only: a penumbra has no 0/1 edge
    std::optional<double> lightBleedingRate;  // filtered techniques only
    // Area lights only (oracle stderr present): the mean error where the oracle's V is strictly
    // between 0 and 1, and its signed mean (too hard < 0 < too soft); where it is exactly 0 and 1.
    std::optional<double> penumbraMae, penumbraBias, umbraMae, litMae;
    // Area lights only: wrong pixels just outside the oracle's penumbra that the technique's own
    // penumbra, too wide or shifted, covers (docs/metrics.md), over counted pixels.
    std::optional<double> penumbraSpreadRate;
    std::optional<PenumbraWidthError> penumbraWidth;  // area lights with a measurable penumbra
    // With the raster's NAME.aliasing_pred: its mean over counted pixels, and the Pearson
    // correlation of its log with the boundary displacement at the raster's boundary pixels.
    std::optional<double> predictedAliasingMean, aliasingCorrelation;
    // With MetricOptions::truthChanged: counted pixels whose truth changed, away (more than r)
    // from the oracle's boundary and outside its penumbra (area lights), and those of them that
    // are wrong (false shadow or false lit):
    // the ghosting class. Summed over a sequence's frames into sequence.ghosting_rate; not in
    // toJson (a row's own metrics describe one frame).
    size_t ghostingEligible = 0, ghostingPixels = 0;
    nlohmann::json toJson() const;
};

// Per-pixel error classes, for the error EXRs and the report's maps: 1 where the pixel counts
// towards that class's metric as an error, else 0; `error` is the pixel's error (see mae).
struct ErrorMaps {
    std::array<std::vector<float>, kArtifactCount> classes;  // by Artifact
    std::vector<float> error;
    // The one class each wrong pixel is drawn as (1 + its Artifact; 0: not a wrong pixel): the
    // classes in order of precedence, so these add up to the false-shadow and false-lit pixels.
    std::vector<uint8_t> shown;
    // 1 where the pixel counts (counted_pixels: both hit the same triangle, facing the light).
    std::vector<uint8_t> counted;
    std::vector<float>& of(Artifact a) { return classes[size_t(a)]; }
    const std::vector<float>& of(Artifact a) const { return classes[size_t(a)]; }
};

// What a technique's shadows cost, beside its metrics in every row of metrics.json.
// An external image's (compare --image) are what its cost file says, each possibly unknown:
// null in metrics.json and empty in the tables, never 0.
struct TechniqueCost {
    std::optional<TimingStats> shadowMapMs, visibilityMs, frameMs;  // over the timed frames
    // The camera pass (shared by the lights: the same in each row).
    std::optional<TimingStats> cameraMs;
    std::optional<uint64_t> memoryBytes;  // GL memory the technique holds for this light
    // A technique that precomputes (lightmaps): the light's bake before the first frame, wall
    // time; in no frame time. Null for every other technique.
    std::optional<double> bakeMs;
    // The light's passes' work in one frame (docs/metrics.md, "Work"); none for an image.
    std::optional<WorkCounts> work;
    // An external image's times are one figure each, not a median of frames: no quartiles.
    bool quartiles = true;
    double oracleSeconds = 0.0;  // what the ground truth of this light cost
    // Sampled area lights: the oracle's time until its penumbra's mean stated 95% half-width came
    // down to this technique's penumbra_mae (tradeoff.h); none for hard lights, or when its run
    // ended above it.
    std::optional<double> oracleMsAtEqualError;
    // A spread above 20% of the median in any of the three times (TimingStats::noisy).
    bool noisy() const {
        for (const auto* t : {&shadowMapMs, &visibilityMs, &frameMs})
            if (quartiles && *t && (*t)->noisy()) return true;
        return false;
    }
    nlohmann::json toJson() const;
};

// One technique against the oracle for one light: a row of metrics.json.
struct LightComparison {
    std::string light;
    LightMetrics metrics;
    TechniqueCost cost;
    ErrorMaps maps;
    // compare --frames-path only: along the scene's camera path (temporal.h).
    std::optional<TemporalFlicker> temporal;
    // compare --sequence only: over the scene's sequence (sequence_metrics.h).
    std::optional<SequenceMetrics> sequence;
    nlohmann::json toJson() const;  // metrics with "cost" (and the temporal and sequence ones)
};

// The metrics of a row by their public names: nested ones joined by a dot
// ("boundary_displacement_px.p95", "cost.frame_ms"), in the row's order. metrics.csv's columns and
// the gate's limits both use these names.
std::vector<std::pair<std::string, nlohmann::json>> flatMetrics(const nlohmann::json& row);

// `oracle` and `raster` follow docs/exr-channels.md; `light` names the light. `maps`, if given,
// receives the per-pixel classes.
LightMetrics computeLightMetrics(const ChannelImage& oracle, const ChannelImage& raster,
                                 const std::string& light, const MetricOptions& options,
                                 ErrorMaps* maps = nullptr);

}  // namespace so
