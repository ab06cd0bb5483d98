// The exact penumbra pass (docs/oracle.md, "Exact penumbrae"): after an area light's sampled pass,
// the pixels it found in a penumbra (their samples disagreed), or every pixel it sampled, get V
// without sampling: exact for rect lights (polygon_visibility.h), in a guaranteed interval of a
// requested half-width for disk and sphere lights (disk_bounds.h), where the sampled pass gives a
// statistical one. The two methods
// share nothing but the scene (Embree and sampling there; clipping in double and integers here),
// so each checks the other (`--penumbra both`).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "oracle/area_light.h"
#include "oracle/disk_bounds.h"
#include "oracle/exact_scene.h"
#include "oracle/stat_fields.h"
#include "oracle/surface_buffer.h"

namespace so {

class Progress;

// `--penumbra`: which method gives an area light's V.
enum class PenumbraMethod : uint8_t {
    Sampled,  // RQMC with 95% intervals (area_shadow.h)
    Exact,    // the exact pass replaces V where it applies (stderr 0 there; disk and sphere
              // lights: V the bound's midpoint, its half-width in NAME.bound)
    Both,     // V stays sampled; V_exact beside it, and their disagreement in oracle.json
};
const char* penumbraMethodName(PenumbraMethod m);
// "sampled", "exact" or "both"; InputError naming file and field otherwise.
PenumbraMethod parsePenumbraMethod(const std::string& text, const std::string& file,
                                   const std::string& field);

// `--exact-pixels`: "penumbra" (false) or "all" (true); InputError naming file and field otherwise.
bool parseExactPixels(const std::string& text, const std::string& file, const std::string& field);

struct ExactPenumbraOptions {
    PenumbraMethod method = PenumbraMethod::Sampled;
    bool allPixels = false;  // every sampled pixel, not only those whose samples disagreed
    // Triangles the pyramid from a point to the light may hold before the pixel keeps its
    // sampled V (the pass's work per pixel grows with them).
    uint32_t maxOccluders = 100000;
    // Disk and sphere lights: the half-width to reach, and the polygons' sides that may be spent.
    DiskBoundOptions bound;
};

// `options` with maxSides checked (a power of two in [minSides, kMaxDiskSides]) and the target
// positive; InputError naming file and field otherwise.
DiskBoundOptions checkedBoundOptions(const DiskBoundOptions& options, const std::string& file,
                                     const std::string& field);

// What a light's exact pixels state as their error (oracle.json's `error_kind`): "exact" (rect
// lights: none beyond rounding) or "bound" (disk and sphere lights: V +- NAME.bound, guaranteed).
const char* exactErrorKind(LightType type);

// Occluder counts in powers of two: bucket 0 holds 0, bucket k holds [2^(k-1), 2^k). Bands of a
// tiled trace add up exactly (trace-merge).
inline constexpr int kOccluderBuckets = 24;
using OccluderHistogram = std::array<uint64_t, kOccluderBuckets>;
// The upper end of the bucket that holds the q-quantile (q in (0, 1]): an upper bound on it.
uint64_t occluderQuantileBound(const OccluderHistogram& h, double q);

struct ExactPenumbraStats {
    PenumbraMethod method = PenumbraMethod::Exact;
    bool allPixels = false;
    // Set when the light kept its sampled V everywhere (a light type the pass does not take).
    std::string notApplied;
    std::string errorKind = "exact";  // exactErrorKind
    DiskBoundOptions bound;           // errorKind "bound" only
    uint64_t pixelsExact = 0;
    uint64_t pixelsTooManyOccluders = 0;  // kept sampled
    uint64_t pixelsAlphaTested = 0;       // kept sampled: an alpha-tested triangle in the pyramid
    uint64_t occludersTotal = 0, occludersMax = 0;  // over the exact pixels
    OccluderHistogram occluders{};
    uint64_t candidatesTotal = 0;  // triangles the BVH query returned
    // Both: exact pixels where the exact V lies outside the sampled 95% interval, and the
    // largest and summed |V_exact - V|.
    uint64_t outsideInterval = 0;
    double maxAbsDifference = 0.0, sumAbsDifference = 0.0;
    // errorKind "bound": the exact pixels' half-widths, the polygons' sides of their last bounds,
    // and the pixels where the sides' cap stopped the doubling before the target.
    double boundHalfWidthMax = 0.0, boundHalfWidthSum = 0.0;
    uint64_t boundSidesMax = 0, boundSidesTotal = 0, boundTargetMissed = 0;
    double seconds = 0.0;
    // The counters (stat_fields.h); the "disagreement." ones are written with Both only, the
    // "bound." ones with errorKind "bound" only.
    static std::span<const StatField<ExactPenumbraStats>> fields();
};

// The per-pixel planes the pass reads and writes. V and stderr_ are the sampled pass's (Exact
// overwrites them where it applies); Vexact (Both only), exactMask (1 where exact, else 0) and
// bound (disk and sphere lights only: the exact pixels' half-widths, else 0) are written in full.
struct ExactPenumbraPlanes {
    float* V = nullptr;
    float* stderr_ = nullptr;
    const float* spp = nullptr;
    float* Vexact = nullptr;
    float* exactMask = nullptr;
    float* bound = nullptr;
};

// Runs inside the caller's task arena; the result is the same at any thread count.
ExactPenumbraStats exactPenumbraPass(const ExactScene& exact, const SurfaceBuffer& sb,
                                     const AreaLight& light, const ExactPenumbraOptions& options,
                                     const ExactPenumbraPlanes& planes, Progress* progress);

}  // namespace so
