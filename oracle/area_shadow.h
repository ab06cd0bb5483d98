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
// spread stated. The estimate and its interval from the replicas' sums: replica_estimate.h.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/channels.h"
#include "core/trace_option_table.h"

#include "oracle/accel.h"
#include "oracle/area_light.h"
#include "oracle/pass_stats.h"
#include "oracle/replica_estimate.h"
#include "oracle/surface_buffer.h"

namespace so {

class Progress;

// Adaptive runs check the stopping rule from this many samples on (4 points per replica).
inline constexpr int kMinAdaptiveSpp = 64;

struct AreaSampling {
    double targetError = 0.01;  // 95% half-width
    // Pixels whose samples all agree stop at max(targetError, agreementTarget) (above).
    double agreementTarget = 0.01;
    int maxSpp = kDefaultMaxSpp;  // the trace option table's default
    int fixedSpp = 0;             // > 0: exactly this many samples per pixel, no adaptivity
    uint32_t seed = 0;
};

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
