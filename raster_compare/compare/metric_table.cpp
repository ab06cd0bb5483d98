#include "raster_compare/compare/metric_table.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "raster_compare/compare/metrics.h"

namespace so {

namespace {

using U = MetricUnit;
using B = Better;
using S = MetricScope;
using A = CostAxis;
using Json = nlohmann::json;

// A cost's value as TechniqueCost::toJson writes it (MetricInfo::cost): null where unknown, the
// quartiles of an external image's one figure included.
template <std::optional<TimingStats> TechniqueCost::*T>
Json medianCost(const TechniqueCost& c) {
    return c.*T ? Json((c.*T)->median) : Json(nullptr);
}
template <std::optional<TimingStats> TechniqueCost::*T, double TimingStats::*Q>
Json quartileCost(const TechniqueCost& c) {
    return c.*T && c.quartiles ? Json(*(c.*T).*Q) : Json(nullptr);
}
template <auto Member>
Json optionalCost(const TechniqueCost& c) {
    return c.*Member ? Json(*(c.*Member)) : Json(nullptr);
}
template <uint64_t WorkCounts::*F>
Json workCost(const TechniqueCost& c) {
    return c.work ? Json(*c.work.*F) : Json(nullptr);
}

// The baseline's built-in tolerances (docs/gate.md#baseline): V and share metrics abs 0.001 + rel
// 5% (the limits file's baseline.default replaces both), widened by the oracle's stated
// uncertainty for means of V errors; pixel distances a quarter pixel (the penumbra profiles' step)
// + 5%; costs, compared only when named, 0.5 ms + 50% (timings of one frame on a shared machine),
// and memory and work, which are exact, 1%.
constexpr Tolerance kFine{0.001, 0.05}, kPixels{0.25, 0.05}, kTime{0.5, 0.5}, kExact{0.0, 0.01};
constexpr BaselineRule kShare{BaselineRule::ByDefault, kFine, OracleNoise::None},
    kMeanV{BaselineRule::ByDefault, kFine, OracleNoise::MeanHalfWidth},
    kWorstV{BaselineRule::ByDefault, kFine, OracleNoise::WorstHalfWidth},
    kPx{BaselineRule::ByDefault, kPixels, OracleNoise::None},
    kTimed{BaselineRule::WhenNamed, kTime, OracleNoise::None},
    kCounted{BaselineRule::WhenNamed, kExact, OracleNoise::None};

// One row per name. The descriptions are one sentence each: docs/metrics.md's prose below the
// generated table has the exact definitions (thresholds, the oracle's interval h, the radius r).
constexpr auto kMetrics = std::to_array<MetricInfo>({
    {"counted_pixels", U::Count, B::None, S::All,
     "pixels that count: both paths hit the same triangle, facing the light"},
    {"excluded_share.background", U::Share, B::None, S::All,
     "share of all pixels left out because either path missed"},
    {"excluded_share.different_surface", U::Share, B::None, S::All,
     "share of all pixels left out because the two paths hit different triangles"},
    {"excluded_share.facing_away", U::Share, B::None, S::All,
     "share of all pixels left out because the surface faces away from the light"},
    {"mae", U::V, B::Lower, S::All,
     "mean error over counted pixels (beyond the oracle's 95% interval on area lights)", nullptr,
     kMeanV},
    {"rmse", U::V, B::Lower, S::All, "root mean square error over counted pixels", nullptr, kMeanV},
    {"max_abs", U::V, B::Lower, S::All, "largest error over counted pixels", nullptr, kWorstV},
    {"false_shadow_rate", U::Share, B::Lower, S::All,
     "share of counted pixels the technique makes darker than the oracle by more than 0.5 (hard "
     "lights) or the oracle's interval (area lights)",
     "false shadow", kShare},
    {"false_lit_rate", U::Share, B::Lower, S::All,
     "share of counted pixels the technique makes brighter than the oracle by more than 0.5 (hard "
     "lights) or the oracle's interval (area lights)",
     "false lit", kShare},
    {"acne_rate", U::Share, B::Lower, S::All,
     "among fully lit pixels more than r pixels from an oracle shadow boundary, the share that "
     "are false shadow (on area lights, not penumbra spread; with the raster's depth channels, "
     "only where its own depth comparison shadowed the pixel by its own surface; never for a "
     "family that compares no depth; in a sequence, not ghosting)",
     "acne", kShare},
    {"screen_bleed_rate", U::Share, B::Lower, S::ScreenSpaceFilter,
     "share of counted pixels, fully lit in the oracle, that are false shadow though their own "
     "depth comparison lit them and a screen-space pass darkened them: it carried a "
     "neighbour's shadow over",
     "screen-space bleed"},
    {"penumbra_spread_rate", U::Share, B::Lower, S::AreaLights,
     "share of counted pixels wrong just outside the oracle's penumbra where the technique's own "
     "penumbra, too wide or shifted, covers them",
     "penumbra spread", kShare},
    {"peter_panning_rate", U::Share, B::Lower, S::OccluderDistance,
     "among shadowed pixels whose occluder is nearer than the contact threshold, the share that "
     "are false lit",
     "peter-panning", kShare},
    {"light_leak_distance", U::WorldUnits, B::Lower, S::OccluderDistance,
     "the largest occluder distance among those false-lit pixels (0 if none)", nullptr, kShare},
    {"boundary_displacement_px.mean", U::Pixels, B::Lower, S::All,
     "mean distance between the two images' shadow boundaries, both ways", nullptr, kPx},
    {"boundary_displacement_px.p95", U::Pixels, B::Lower, S::All,
     "95th percentile of the distance between the two images' shadow boundaries", "boundary p95",
     kPx},
    {"boundary_displacement_px.max", U::Pixels, B::Lower, S::All,
     "largest distance between the two images' shadow boundaries", nullptr, kPx},
    {"boundary_displacement_px.missing_boundary", U::Flag, B::None, S::All,
     "true when one image has a shadow boundary and the other none (the distances are then the "
     "image diagonal)"},
    {"boundary_band_mae", U::V, B::Lower, S::All,
     "mean error within r pixels of an oracle shadow boundary (null without one)", nullptr, kMeanV},
    {"aliasing_rate", U::Share, B::Lower, S::HardLights,
     "among counted pixels within r pixels of an oracle shadow boundary, the share that are "
     "wrong",
     "aliasing", kShare},
    {"other_false_shadow_rate", U::Share, B::Lower, S::All,
     "share of counted pixels that are false shadow and that no artifact class explains",
     "other false shadow", kShare},
    {"other_false_lit_rate", U::Share, B::Lower, S::All,
     "share of counted pixels that are false lit and that no artifact class explains",
     "other false lit", kShare},
    {"light_bleeding_rate", U::Share, B::Lower, S::FilteredTechniques,
     "among counted pixels in the oracle's umbra, the share the technique lights by more than "
     "0.1",
     "light bleeding", kShare},
    {"penumbra_mae", U::V, B::Lower, S::AreaLights,
     "mean error over counted pixels where the oracle's V is strictly between 0 and 1",
     "penumbra mae", kMeanV},
    {"penumbra_bias", U::V, B::SmallerMagnitude, S::AreaLights,
     "signed mean error over those pixels: < 0 too hard, > 0 too soft", "penumbra bias", kMeanV},
    {"umbra_mae", U::V, B::Lower, S::AreaLights,
     "mean error over counted pixels where the oracle's V is exactly 0", nullptr, kMeanV},
    {"lit_mae", U::V, B::Lower, S::AreaLights,
     "mean error over counted pixels where the oracle's V is exactly 1", nullptr, kMeanV},
    {"penumbra_width_error_px.mean", U::Pixels, B::Lower, S::AreaLights,
     "mean absolute difference of the penumbra's 10%-90% width, along the oracle's gradient "
     "(null without a measurable penumbra)",
     "width error", kPx},
    {"penumbra_width_error_px.p95", U::Pixels, B::Lower, S::AreaLights,
     "95th percentile of that width difference", nullptr, kPx},
    {"penumbra_width_error_px.oracle_mean_width", U::Pixels, B::None, S::AreaLights,
     "the oracle's own mean 10%-90% width, for scale"},
    {"penumbra_width_error_px.profiles", U::Count, B::None, S::AreaLights,
     "penumbra profiles measured"},
    {"predicted_aliasing.mean", U::Ratio, B::None, S::AliasingPrediction,
     "mean predicted aliasing (a map texel's footprint over a pixel's) over counted pixels"},
    {"predicted_aliasing.correlation_with_boundary_error", U::Correlation, B::None,
     S::AliasingPrediction,
     "correlation of the prediction's log with the boundary displacement at the raster's "
     "boundary pixels (null below 10 of them)"},
    {"cost.shadow_map_ms", U::Ms, B::Lower, S::All,
     "median time of the light's passes before the visibility pass (the map, the volumes)",
     "shadow pass", kTimed, A::Pass, &medianCost<&TechniqueCost::shadowMapMs>},
    {"cost.shadow_map_ms_p25",
     U::Ms,
     B::Lower,
     S::All,
     "its 25th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::shadowMapMs, &TimingStats::p25>},
    {"cost.shadow_map_ms_p75",
     U::Ms,
     B::Lower,
     S::All,
     "its 75th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::shadowMapMs, &TimingStats::p75>},
    {"cost.visibility_ms", U::Ms, B::Lower, S::All, "median time of the visibility pass",
     "visibility pass", kTimed, A::Pass, &medianCost<&TechniqueCost::visibilityMs>},
    {"cost.visibility_ms_p25",
     U::Ms,
     B::Lower,
     S::All,
     "its 25th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::visibilityMs, &TimingStats::p25>},
    {"cost.visibility_ms_p75",
     U::Ms,
     B::Lower,
     S::All,
     "its 75th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::visibilityMs, &TimingStats::p75>},
    {"cost.camera_ms", U::Ms, B::Lower, S::All,
     "median time of the camera pass, shared by the scene's lights", "camera pass", kTimed, A::None,
     &medianCost<&TechniqueCost::cameraMs>},
    {"cost.camera_ms_p25",
     U::Ms,
     B::Lower,
     S::All,
     "its 25th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::cameraMs, &TimingStats::p25>},
    {"cost.camera_ms_p75",
     U::Ms,
     B::Lower,
     S::All,
     "its 75th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::cameraMs, &TimingStats::p75>},
    {"cost.frame_ms", U::Ms, B::Lower, S::All,
     "median frame time: the light's passes and the camera pass", "frame time", kTimed, A::Frame,
     &medianCost<&TechniqueCost::frameMs>},
    {"cost.frame_ms_p25",
     U::Ms,
     B::Lower,
     S::All,
     "its 25th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::frameMs, &TimingStats::p25>},
    {"cost.frame_ms_p75",
     U::Ms,
     B::Lower,
     S::All,
     "its 75th percentile over the frames",
     nullptr,
     {},
     A::None,
     &quartileCost<&TechniqueCost::frameMs, &TimingStats::p75>},
    {"cost.noisy",
     U::Flag,
     B::None,
     S::All,
     "true when any of the times spreads (p25 to p75) by more than 20% of its median",
     nullptr,
     {},
     A::None,
     [](const TechniqueCost& c) { return Json(c.noisy()); }},
    {"cost.memory_bytes", U::Bytes, B::Lower, S::All, "GL memory the technique holds for the light",
     "memory", kCounted, A::Memory, &optionalCost<&TechniqueCost::memoryBytes>},
    {"cost.bake_ms", U::Ms, B::Lower, S::BakedTechniques,
     "the light's bake before the first frame (lightmap), wall time; not part of frame_ms", nullptr,
     kTimed, A::None, &optionalCost<&TechniqueCost::bakeMs>},
    {"cost.work.fragments", U::Count, B::Lower, S::All,
     "fragment shader invocations of the light's passes in a frame (depth tested first where the "
     "shader cannot discard)",
     "fragments", kCounted, A::Work, &workCost<&WorkCounts::fragments>},
    {"cost.work.texture_taps", U::Count, B::Lower, S::All,
     "texture lookups of the light's passes in a frame (a filtered lookup is one)", "texture taps",
     kCounted, A::Work, &workCost<&WorkCounts::textureTaps>},
    {"cost.work.texels_written", U::Count, B::Lower, S::All,
     "render-target texels the light's passes write in a frame, each once per pass",
     "texels written", kCounted, A::Work, &workCost<&WorkCounts::texelsWritten>},
    {"cost.work.bytes_moved", U::Bytes, B::Lower, S::All,
     "render-target bytes the light's passes write and read (each texel once per pass) and the "
     "bytes their taps fetch, in a frame",
     "bytes moved", kCounted, A::Work, &workCost<&WorkCounts::bytesMoved>},
    {"cost.work.draw_calls", U::Count, B::Lower, S::All,
     "draw calls of the light's passes in a frame", "draw calls", kCounted, A::Work,
     &workCost<&WorkCounts::drawCalls>},
    {"cost.work.passes", U::Count, B::Lower, S::All,
     "passes the light runs in a frame (a pass per sample counts per sample)", "passes", kCounted,
     A::Work, &workCost<&WorkCounts::passes>},
    {"cost.work.rays_traced", U::Count, B::Lower, S::All,
     "shadow rays traced for the light in a frame (the raytraced family; 0 elsewhere)",
     "rays traced", kCounted, A::Work, &workCost<&WorkCounts::raysTraced>},
    {"cost.oracle_seconds",
     U::Seconds,
     B::None,
     S::All,
     "what the ground truth of the light cost",
     nullptr,
     {},
     A::None,
     [](const TechniqueCost& c) { return Json(c.oracleSeconds); }},
    {"cost.oracle_ms_at_equal_error",
     U::Ms,
     B::None,
     S::AreaLights,
     "the oracle's time until its penumbra's mean 95% half-width came down to this technique's "
     "penumbra_mae",
     "oracle at equal error",
     {},
     A::None,
     &optionalCost<&TechniqueCost::oracleMsAtEqualError>},
    {"temporal_flicker_rate", U::Share, B::Lower, S::FramesPath,
     "share of tracked pixel pairs of consecutive frames whose V flips where the oracle's does "
     "not",
     "temporal flicker", kShare},
    {"temporal_tracked_pairs", U::Count, B::None, S::FramesPath,
     "pixel pairs tracked, summed over the frame pairs"},
    {"temporal_flickering_pairs", U::Count, B::None, S::FramesPath,
     "pixel pairs that flicker, summed over the frame pairs"},
    {"temporal_frames", U::Count, B::None, S::FramesPath, "frames along the camera path"},
    {"sequence.frames", U::Count, B::None, S::Sequence,
     "frames of the scene's sequence, each judged against its own oracle (mae_per_frame, a "
     "series, is in metrics.json only)",
     "sequence frames"},
    {"sequence.mae_mean", U::V, B::Lower, S::Sequence, "mae averaged over the sequence's frames",
     "sequence mae"},
    {"sequence.mae_last", U::V, B::Lower, S::Sequence,
     "mae of the sequence's last frame (the frame the row's other metrics describe)",
     "last frame mae"},
    {"sequence.flicker_rate", U::Share, B::Lower, S::Sequence,
     "share of pixel pairs of consecutive frames, tracked through the camera's and the meshes' "
     "known motion, whose V changes by more than 0.1 where the oracle's does not",
     "sequence flicker"},
    {"sequence.tracked_pairs", U::Count, B::None, S::Sequence,
     "pixel pairs tracked, summed over the sequence's frame pairs"},
    {"sequence.flickering_pairs", U::Count, B::None, S::Sequence,
     "pixel pairs that flicker, summed over the sequence's frame pairs"},
    {"sequence.lag_mae", U::V, B::Lower, S::Sequence,
     "mean error over the counted pixels whose oracle V changed by more than 0.5 within the 4 "
     "frames before, pooled over the frames (null where the truth never changed): lag and "
     "ghosting",
     "lag mae"},
    {"sequence.lag_pixels", U::Count, B::None, S::Sequence,
     "pixel-frames lag_mae is the mean over"},
    {"sequence.ghosting_rate", U::Share, B::Lower, S::Sequence,
     "among lag_mae's pixel-frames more than r pixels from the frame's oracle shadow boundary "
     "(on area lights, outside its penumbra), the share that are false shadow or false lit: an "
     "old shadow or light kept (null where the truth never changed away from an edge)",
     "ghosting"},
    {"sequence.ghosting_pixels", U::Count, B::None, S::Sequence,
     "pixel-frames counted as ghosting, summed over the frames"},
});

// Levenshtein distance, for suggestions on a misspelled limit.
size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

}  // namespace

std::span<const MetricInfo> allMetrics() {
    return kMetrics;
}

const MetricInfo* findMetric(const std::string& name) {
    for (const MetricInfo& m : kMetrics)
        if (name == m.name) return &m;
    return nullptr;
}

const MetricInfo& metricInfo(const std::string& name) {
    const MetricInfo* m = findMetric(name);
    SO_CHECK(m != nullptr);
    return *m;
}

std::vector<const MetricInfo*> costAxes(bool passes) {
    std::vector<const MetricInfo*> out;
    for (const A kind : {A::Frame, A::Pass, A::Memory, A::Work})
        for (const MetricInfo& m : kMetrics)
            if (m.costAxis == kind && (passes || kind != A::Pass)) out.push_back(&m);
    return out;
}

bool isMetricGroup(const std::string& name) {
    const std::string prefix = name + ".";
    return std::any_of(kMetrics.begin(), kMetrics.end(), [&](const MetricInfo& m) {
        return std::string(m.name).starts_with(prefix);
    });
}

std::vector<std::string> nearestMetrics(const std::string& name, size_t count) {
    std::vector<std::string> out;
    if (isMetricGroup(name)) {
        for (const MetricInfo& m : kMetrics)
            if (std::string(m.name).starts_with(name + ".") && out.size() < count)
                out.push_back(m.name);
        return out;
    }
    // Close enough to be a typo: a third of the name's length, at least two edits. A name from a
    // hostile file may be long; one far longer than any metric is no typo (and the distance would
    // cost its length times each name's).
    if (name.size() > 80) return out;
    const size_t limit = std::max<size_t>(2, name.size() / 3);
    std::vector<std::pair<size_t, std::string>> near;
    for (const MetricInfo& m : kMetrics)
        if (const size_t d = editDistance(name, m.name); d <= limit) near.emplace_back(d, m.name);
    std::stable_sort(near.begin(), near.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t i = 0; i < near.size() && i < count; ++i) out.push_back(near[i].second);
    return out;
}

const char* unitName(MetricUnit u) {
    switch (u) {
        case U::V:
            return "V";
        case U::Share:
            return "share";
        case U::Pixels:
            return "px";
        case U::WorldUnits:
            return "world units";
        case U::Ms:
            return "ms";
        case U::Seconds:
            return "s";
        case U::Bytes:
            return "bytes";
        case U::Count:
            return "count";
        case U::Ratio:
            return "ratio";
        case U::Correlation:
            return "r";
        case U::Flag:
            return "true/false";
    }
    return "";
}

const char* betterName(Better b) {
    switch (b) {
        case B::Lower:
            return "lower";
        case B::Higher:
            return "higher";
        case B::SmallerMagnitude:
            return "nearer 0";
        case B::None:
            return "none";
    }
    return "";
}

const char* scopeName(MetricScope s) {
    switch (s) {
        case S::All:
            return "all";
        case S::HardLights:
            return "hard lights";
        case S::AreaLights:
            return "area lights";
        case S::FilteredTechniques:
            return "filtered techniques";
        case S::ScreenSpaceFilter:
            return "with `V_unfiltered`";
        case S::OccluderDistance:
            return "with `occ_dist`";
        case S::AliasingPrediction:
            return "with `aliasing_pred`";
        case S::FramesPath:
            return "`--frames-path`";
        case S::Sequence:
            return "`--sequence`";
        case S::BakedTechniques:
            return "baked techniques";
    }
    return "";
}

std::string metricLabel(const MetricInfo& m) {
    return m.label ? m.label : m.name;
}

std::string formatMetricValue(const MetricInfo& m, double v) {
    char buf[32];
    switch (m.unit) {
        case U::V:
            std::snprintf(buf, sizeof buf, m.better == B::SmallerMagnitude ? "%+.3f" : "%.4f", v);
            break;
        case U::Share:
            std::snprintf(buf, sizeof buf, "%.2f%%", 100.0 * v);
            break;
        case U::Pixels:
        case U::Seconds:
            std::snprintf(buf, sizeof buf, "%.2f", v);
            break;
        case U::Ms:
            std::snprintf(buf, sizeof buf, v < 10.0 ? "%.2f" : "%.1f", v);
            break;
        case U::Bytes:
            std::snprintf(buf, sizeof buf, "%.2f", v * displayScale(m));
            break;
        case U::Count:  // 3 significant digits with k, M, G beyond a thousand
            if (v < 1e3)
                std::snprintf(buf, sizeof buf, "%.0f", v);
            else if (v < 1e6)
                std::snprintf(buf, sizeof buf, "%.3g k", v / 1e3);
            else if (v < 1e9)
                std::snprintf(buf, sizeof buf, "%.3g M", v / 1e6);
            else
                std::snprintf(buf, sizeof buf, "%.3g G", v / 1e9);
            break;
        case U::Flag:
            return v != 0.0 ? "true" : "false";
        case U::WorldUnits:
        case U::Ratio:
            std::snprintf(buf, sizeof buf, "%.4g", v);
            break;
        case U::Correlation:
            std::snprintf(buf, sizeof buf, "%+.2f", v);
            break;
    }
    return buf;
}

const char* displayUnit(const MetricInfo& m) {
    switch (m.unit) {
        case U::Pixels:
            return "px";
        case U::Ms:
            return "ms";
        case U::Seconds:
            return "s";
        case U::Bytes:
            return "MiB";
        case U::Count:
            return "count";
        case U::WorldUnits:
            return "world units";
        default:
            return "";
    }
}

double displayScale(const MetricInfo& m) {
    return m.unit == U::Bytes ? 1.0 / 1048576.0 : 1.0;
}

std::string metricTableMarkdown() {
    std::ostringstream o;
    o << "| metric | unit | better | where | meaning |\n|---|---|---|---|---|\n";
    for (const MetricInfo& m : kMetrics)
        o << "| `" << m.name << "` | " << unitName(m.unit) << " | " << betterName(m.better) << " | "
          << scopeName(m.scope) << " | " << m.description << " |\n";
    return o.str();
}

}  // namespace so
