// Penumbrae by sampling: per pixel, batches of 16 shadow rays (one coherent packet) towards
// Owen-scrambled Sobol points on the light, until the pixel's 95% interval is narrow enough.
//
// The estimate is V = sum w v / sum w (area_light.h). Its interval is V +- 1.96 * stderr, with
// stderr from the delta-method variance of the ratio estimator, computed as if the samples were
// independent (they are stratified, so this overstates the error: the intervals are conservative)
// and with an Agresti-Coull-style prior of 1.92 pseudo-samples lit and 1.92 shadowed at the mean
// weight, so that a pixel whose samples all agree is not declared certain: 16 of 16 lit gives
// stderr 0.066, and an always-lit pixel needs ~270 samples before its half-width is below 0.01.
//
// Stopping rule (adaptive): after each batch, stop when 1.96 * stderr <= target error or the
// pixel has max_spp samples. With a fixed count (--spp N), exactly N samples.
#pragma once

#include <cstdint>

#include "oracle/accel.h"
#include "oracle/area_light.h"
#include "oracle/surface_buffer.h"

namespace so {

class Progress;

// Two-sided 95% normal quantile: every interval the oracle states is V +- kZ95 * stderr.
inline constexpr double kZ95 = 1.959963984540054;

struct AreaSampling {
    double targetError = 0.01;  // 95% half-width
    int maxSpp = 16384;
    int fixedSpp = 0;  // > 0: exactly this many samples per pixel, no adaptivity
    uint32_t seed = 0;
};

struct AreaShadowStats {
    uint64_t samples = 0, raysTraced = 0, raysOccluded = 0;
    uint64_t pixelsSampled = 0, reachedTarget = 0, maxSpp = 0;
    // Pixels where the light is above the horizon only by a sliver no sample found: reported as
    // V = 0 with the widest interval, and left out of worstHalfWidth (they carry no estimate).
    uint64_t pixelsWithoutUsableSamples = 0;
    uint64_t skippedBackground = 0, skippedBelowHorizon = 0, skippedBehindLight = 0,
             skippedInsideLight = 0;
    double worstHalfWidth = 0.0;  // the largest 1.96 * stderr over sampled pixels
    double uniformSppForWorst =
        0.0;  // spp a uniform run needs for that worst half-width everywhere
    double samplingEfficiency = 1.0;  // mean over pixels of Kish's n_eff / n for the weights
    double seconds = 0.0;
};

// Half-width and standard error of the estimate from the running sums (exposed for tests).
struct RatioEstimate {
    double V = 0.0, stderr_ = 0.0;
};
RatioEstimate ratioEstimate(double sw, double swv, double sw2, double sw2v, uint64_t nonZero);

// The seed of one pixel's sample sequence: `stream` separates lights, `pixel` is the row-major
// pixel index. The sequence depends on nothing else, so the image is the same at any thread count.
uint32_t areaPixelSeed(uint32_t seed, uint32_t stream, uint32_t pixel);

// `stream` separates the sample sequences of different lights. Writes V, stderr, spp and cos
// (towards the centre) per pixel. Runs in parallel inside the caller's task arena.
AreaShadowStats traceAreaShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const AreaLight& light, const AreaSampling& sampling,
                                 uint32_t stream, float* V, float* stderr_, float* spp,
                                 float* cosine, Progress* progress);

}  // namespace so
