// The exact penumbra pass (docs/oracle.md, "Exact penumbrae"): V without sampling, exact for
// rect lights (polygon_visibility.h), with a stated error (about 1e-8) for disk and sphere lights
// (disk_exact.h), where the sampled pass gives a statistical one. With
// `--penumbra exact` the pass finds its own pixels: every pixel the camera hit, before any
// sampling (a pixel whose pyramid holds no occluder is lit without a union, one whose shadows
// cover the light is dark as soon as they do); the sampled pass then runs only on the pixels the
// exact pass cannot answer. With `--penumbra both` it runs after the sampled pass, on the pixels
// whose samples disagreed (or every sampled pixel). The two methods share nothing but the scene
// (Embree and sampling there; clipping in double and integers here), so each checks the other.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "oracle/area_light.h"
#include "oracle/disk_bounds.h"
#include "oracle/exact_scene.h"
#include "oracle/mesh_facing.h"
#include "oracle/stat_fields.h"
#include "oracle/surface_buffer.h"

namespace so {

class Progress;

// `--penumbra`: which method gives an area light's V.
enum class PenumbraMethod : uint8_t {
    Sampled,  // RQMC with 95% intervals (area_shadow.h)
    Exact,    // the exact pass gives V on every pixel it applies to (stderr 0 there; disk and
              // sphere lights: V with its stated error in NAME.bound)
    Both,     // V stays sampled; V_exact beside it, and their disagreement in oracle.json
    Auto,  // per light, Exact or Sampled, whichever a probe estimates cheaper (penumbra_choice.h)
};
const char* penumbraMethodName(PenumbraMethod m);
// "sampled", "exact", "both" or "auto"; InputError naming file and field otherwise.
PenumbraMethod parsePenumbraMethod(const std::string& text, const std::string& file,
                                   const std::string& field);

// `--exact-pixels`: "penumbra" (false) or "all" (true); InputError naming file and field otherwise.
bool parseExactPixels(const std::string& text, const std::string& file, const std::string& field);

struct ExactPenumbraOptions {
    PenumbraMethod method = PenumbraMethod::Auto;  // the default of trace, compare and the API
    // Both: every sampled pixel, not only those whose samples disagreed. (Exact finds its own
    // pixels: every pixel the camera hit.)
    bool allPixels = false;
    // The lit and covered shortcuts (occluder_union.h); tests turn them off to check that they
    // change nothing.
    bool shortcuts = true;
    // Back faces of closed meshes left out of the union where the camera tells the side
    // (mesh_facing.h); tests turn it off to check that it changes nothing.
    bool backFaces = true;
    // Whole triangles' shadows merged along their shared edges before the union
    // (occluder_union.h); tests turn it off to check that it changes nothing.
    bool merge = true;
    // Triangles the pyramid from a point to the light may hold before the pixel keeps its
    // sampled V (the pass's work per pixel grows with them).
    uint32_t maxOccluders = 100000;
    // Disk and sphere lights: the stated error beyond which a pixel counts as missing the target
    // (disk_exact.h); maxSides is the polygons' bound's (disk_bounds.h, the independent check).
    DiskBoundOptions bound;
};

// `options` with maxSides checked (a power of two in [minSides, kMaxDiskSides]) and the target
// positive; InputError naming file and field otherwise.
DiskBoundOptions checkedBoundOptions(const DiskBoundOptions& options, const std::string& file,
                                     const std::string& field);

// What a light's exact pixels state as their error (oracle.json's `error_kind`): "exact" (rect
// lights: none beyond rounding) or "bound" (disk and sphere lights: V +- NAME.bound, the stated
// error).
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
    // Of the exact pixels, those answered without a union: no triangle in the pyramid (V = 1), the
    // shadows found to cover the light (V = 0), no light above the horizon (V = 0).
    uint64_t pixelsLit = 0, pixelsCovered = 0, pixelsNoLight = 0;
    uint64_t pixelsTooManyOccluders = 0;  // kept sampled
    uint64_t pixelsAlphaTested = 0;       // kept sampled: an alpha-tested triangle in the pyramid
    uint64_t occludersTotal = 0, occludersMax = 0;  // over the exact pixels
    OccluderHistogram occluders{};
    uint64_t candidatesTotal = 0;  // triangles the BVH query returned
    uint64_t backFacesTotal = 0;   // of those, back faces left out (mesh_facing.h)
    // Both: exact pixels where the exact V lies outside the sampled 95% interval, and the
    // largest and summed |V_exact - V|.
    uint64_t outsideInterval = 0;
    double maxAbsDifference = 0.0, sumAbsDifference = 0.0;
    // errorKind "bound": the exact pixels' stated errors (disk_exact.h), the gathering polygon's
    // sides where the contour was integrated (0 where a shortcut answered), and the pixels whose
    // stated error is above --bound-target.
    double boundHalfWidthMax = 0.0, boundHalfWidthSum = 0.0;
    uint64_t boundSidesMax = 0, boundSidesTotal = 0, boundTargetMissed = 0;
    double seconds = 0.0;
    // The counters (stat_fields.h); the "disagreement." ones are written with Both only, the
    // "bound." ones with errorKind "bound" only.
    static std::span<const StatField<ExactPenumbraStats>> fields();
};

// --penumbra auto (penumbra_choice.h): what the probe found for one light, and the method it
// chose (oracle.json lights[].penumbra_choice).
struct PenumbraChoice {
    PenumbraMethod chosen = PenumbraMethod::Sampled;  // Exact or Sampled
    std::string reason;
    // The probe: its points that the camera hit, the shadow rays the sampled pass traced on them
    // to the target, and the exact pass's pyramids' triangles (candidates the BVH query returned,
    // and occluders whose shadows reached the union) and its points it could not answer; disk and
    // sphere lights: the gathering polygon's sides summed over the points whose contour was
    // integrated (disk_exact.h; else 0).
    uint64_t probePoints = 0, probeRays = 0, probeCandidates = 0, probeOccluders = 0,
             probeKeptSampled = 0, probeBoundSides = 0;
    // The estimates for this image (or band): the probe's counts in processor seconds, scaled by
    // the image's points over the probe's.
    double exactSeconds = 0.0, sampledSeconds = 0.0;
};

// The per-pixel planes the pass reads and writes; Vexact (Both only), exactMask (1 where exact,
// else 0) and bound (disk and sphere lights only: the exact pixels' half-widths, else 0) are
// written in full.
// - After the sampled pass (spp set): V and stderr_ are its planes; Exact overwrites them where
//   it applies.
// - Before it (spp null, Exact): the pass finds its own pixels, every slot the camera hit (of
//   `onlySlots` where given), and writes V, stderr_ (0) and cosine there; needsSampling[slot] is
//   set to 1 where it gives no answer (too many occluders, alpha-tested), for the sampled pass.
struct ExactPenumbraPlanes {
    float* V = nullptr;
    float* stderr_ = nullptr;
    const float* spp = nullptr;
    float* Vexact = nullptr;
    float* exactMask = nullptr;
    float* bound = nullptr;
    float* cosine = nullptr;
    std::vector<uint8_t>* needsSampling = nullptr;
    const std::vector<uint8_t>* onlySlots = nullptr;
};

// Runs inside the caller's task arena; the result is the same at any thread count. facing: the
// back faces the camera's points may leave out (mesh_facing.h; null: none, as for a G-buffer's
// points), used where options.backFaces.
ExactPenumbraStats exactPenumbraPass(const ExactScene& exact, const SurfaceBuffer& sb,
                                     const AreaLight& light, const ExactPenumbraOptions& options,
                                     const ExactPenumbraPlanes& planes, Progress* progress,
                                     const MeshFacing* facing = nullptr);

}  // namespace so
