#include "oracle/exact_penumbra.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "core/progress.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/polygon_visibility.h"

namespace so {

namespace {

// In the enum's order.
constexpr std::array<const char*, 4> kMethodNames = {"sampled", "exact", "both", "auto"};

}  // namespace

const char* penumbraMethodName(PenumbraMethod m) {
    return kMethodNames.at(size_t(m));
}

PenumbraMethod parsePenumbraMethod(const std::string& text, const std::string& file,
                                   const std::string& field) {
    for (size_t k = 0; k < kMethodNames.size(); ++k)
        if (text == kMethodNames[k]) return PenumbraMethod(k);
    // The JSON reader's wording for a name not in a list (docs/scene-format.md, "One wording").
    throwInputError(file, field,
                    "unknown value \"" + printable(text, 40) + "\" (valid: " +
                        JsonReader::list({kMethodNames.begin(), kMethodNames.end()}) + ")");
}

bool parseExactPixels(const std::string& text, const std::string& file, const std::string& field) {
    if (text == "penumbra" || text == "all") return text == "all";
    throwInputError(file, field,
                    "unknown value \"" + printable(text, 40) + "\" (valid: penumbra, all)");
}

std::span<const StatField<ExactPenumbraStats>> ExactPenumbraStats::fields() {
    using S = ExactPenumbraStats;
    static constexpr StatField<S> kFields[] = {
        {"pixels_exact", &S::pixelsExact},
        {"pixels_found.lit", &S::pixelsLit},
        {"pixels_found.covered", &S::pixelsCovered},
        {"pixels_found.no_light", &S::pixelsNoLight},
        {"pixels_kept_sampled.too_many_occluders", &S::pixelsTooManyOccluders},
        {"pixels_kept_sampled.alpha_tested", &S::pixelsAlphaTested},
        {"occluders.total", &S::occludersTotal},
        {"occluders.max", &S::occludersMax, Combine::Max},
        {"candidates_total", &S::candidatesTotal},
        {"back_faces_left_out", &S::backFacesTotal},
        {"disagreement.outside_interval", &S::outsideInterval},
        {"disagreement.max_abs", &S::maxAbsDifference, Combine::Max},
        {"disagreement.sum_abs", &S::sumAbsDifference},
        {"bound.half_width_max", &S::boundHalfWidthMax, Combine::Max},
        {"bound.half_width_sum", &S::boundHalfWidthSum},
        {"bound.sides_max", &S::boundSidesMax, Combine::Max},
        {"bound.sides_total", &S::boundSidesTotal},
        {"bound.pixels_target_missed", &S::boundTargetMissed},
        {"seconds", &S::seconds},
    };
    return kFields;
}

DiskBoundOptions checkedBoundOptions(const DiskBoundOptions& options, const std::string& file,
                                     const std::string& field) {
    const uint32_t n = options.maxSides;
    if (n < options.minSides || n > kMaxDiskSides || (n & (n - 1)) != 0)
        throwInputError(file, field,
                        std::to_string(n) + " is not a power of two in [" +
                            std::to_string(options.minSides) + ", " +
                            std::to_string(kMaxDiskSides) + "]");
    if (!(options.targetHalfWidth > 0.0))
        throwInputError(file, field, "the target half-width must be positive");
    return options;
}

const char* exactErrorKind(LightType type) {
    return areaLightKind(type).bounded() ? "bound" : "exact";
}

uint64_t occluderQuantileBound(const OccluderHistogram& h, double q) {
    uint64_t total = 0;
    for (uint64_t c : h) total += c;
    if (total == 0) return 0;
    const double wanted = q * double(total);
    uint64_t seen = 0;
    for (int k = 0; k < kOccluderBuckets; ++k) {
        seen += h[size_t(k)];
        if (double(seen) >= wanted) return k == 0 ? 0 : (uint64_t(1) << k) - 1;
    }
    return (uint64_t(1) << (kOccluderBuckets - 1)) - 1;
}

namespace {

using Clock = std::chrono::steady_clock;

int bucketOf(uint64_t occluders) {
    int k = 0;
    while (occluders > 0 && k < kOccluderBuckets - 1) occluders >>= 1, ++k;
    return k;
}

// Without the sampled pass: the cosine towards the light's centre as it writes it
// (area_shadow.cpp), and V and stderr 0 until an answer replaces them.
void writeCosine(const AreaLight& light, const SurfaceBuffer& sb, size_t s, size_t i,
                 const ExactPenumbraPlanes& planes) {
    const glm::vec3 p = sb.lsPoint(s), n = sb.lsNormal(s);
    planes.cosine[i] = glm::dot(n, glm::normalize(light.lsCenter - p));
    planes.V[i] = planes.stderr_[i] = 0.0f;
}

// What one pixel's exact V came to (status Exact, TooManyOccluders or AlphaTested), or nothing
// asked; disk and sphere lights: the bound's half-width and sides too.
struct PixelAnswer : ExactLightAnswer {
    bool asked = false;
};

// The light seen from p, as its type answers it (oracle/lights/); `more`: the union's shortcuts
// and back faces, which hold for the disk's bound as for a polygon (occluder_union.h).
PixelAnswer answerAt(const ExactScene& exact, const AreaLight& light,
                     const ExactPenumbraOptions& options, const OccluderOptions& more,
                     const glm::dvec3& p, const glm::dvec3& n, TriangleId id) {
    PixelAnswer a;
    static_cast<ExactLightAnswer&>(a) =
        light.kind->exactAt(exact.tracer(), light, options, more, p, n, id);
    a.asked = true;
    return a;
}

// Whether the pass answers slot s (pixel i).
bool selected(const ExactPenumbraOptions& options, const ExactPenumbraPlanes& planes, size_t s,
              size_t i) {
    if (!planes.spp)  // the pass's own pixels: every one the camera hit (sb.hit, checked before)
        return !planes.onlySlots || (*planes.onlySlots)[s] != 0;
    if (!(planes.spp[i] > 0.0f)) return false;  // skipped by the sampled pass: V = 0, exactly
    return options.allPixels || (planes.V[i] > 0.0f && planes.V[i] < 1.0f);
}

// The answers per slot, in parallel; nothing shared is written.
std::vector<PixelAnswer> answers(const ExactScene& exact, const SurfaceBuffer& sb,
                                 const AreaLight& light, const ExactPenumbraOptions& options,
                                 const ExactPenumbraPlanes& planes, Progress* progress,
                                 const MeshFacing* facing) {
    const OccluderOptions more{options.shortcuts, options.merge,
                               options.backFaces ? facing : nullptr};
    std::vector<PixelAnswer> out(sb.slotCount());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sb.slotCount(), 64),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t s = r.begin(); s < r.end(); ++s) {
                              const size_t i = sb.pixelOfSlot(s);
                              if (i == SIZE_MAX || !sb.hit[s] || !selected(options, planes, s, i))
                                  continue;
                              const TriangleId id{sb.meshId[s], sb.primId[s]};
                              const glm::dvec3 p = exact.point(id, sb.baryU[s], sb.baryV[s]);
                              const glm::dvec3 n = exact.normal(id, glm::dvec3(sb.lsNormal(s)));
                              out[s] = answerAt(exact, light, options, more, p, n, id);
                          }
                          if (progress) progress->advance(r.size());
                      });
    return out;
}

// A bounded answer's half-width into its plane and the counts.
// v: the V written, the bound's midpoint rounded to float.
void applyBound(const PixelAnswer& a, float v, size_t i, const ExactPenumbraPlanes& planes,
                ExactPenumbraStats& st) {
    // About the float V, and rounded up: the plane must not state less than the bound.
    const double half = a.halfWidth + std::fabs(double(v) - a.result.V);
    planes.bound[i] = half > 0.0 ? std::nextafter(float(half), 1.0f) : 0.0f;
    st.boundHalfWidthMax = std::max(st.boundHalfWidthMax, a.halfWidth);
    st.boundHalfWidthSum += a.halfWidth;
    st.boundSidesMax = std::max<uint64_t>(st.boundSidesMax, a.sides);
    st.boundSidesTotal += a.sides;
    st.boundTargetMissed += !a.reachedTarget;
}

// One exact answer into the planes and the counts.
void apply(const PixelAnswer& answer, size_t s, size_t i, const ExactPenumbraOptions& options,
           const ExactPenumbraPlanes& planes, ExactPenumbraStats& st) {
    const PolygonVisibility& a = answer.result;
    if (a.status == PolygonVisibilityStatus::TooManyOccluders ||
        a.status == PolygonVisibilityStatus::AlphaTested) {
        ++(a.status == PolygonVisibilityStatus::AlphaTested ? st.pixelsAlphaTested
                                                            : st.pixelsTooManyOccluders);
        if (planes.needsSampling) (*planes.needsSampling)[s] = 1;
        return;
    }
    ++st.pixelsExact;
    st.pixelsNoLight += a.status == PolygonVisibilityStatus::NoLight;
    st.pixelsLit += a.shortcut == VisibilityShortcut::Lit;
    st.pixelsCovered += a.shortcut == VisibilityShortcut::Covered;
    st.occludersTotal += a.occluders;
    st.occludersMax = std::max<uint64_t>(st.occludersMax, a.occluders);
    ++st.occluders[size_t(bucketOf(a.occluders))];
    planes.exactMask[i] = 1.0f;
    const float v = float(a.V);
    if (planes.bound) applyBound(answer, v, i, planes, st);
    if (options.method == PenumbraMethod::Both) {
        planes.Vexact[i] = v;
        const double diff = std::fabs(a.V - double(planes.V[i]));
        st.maxAbsDifference = std::max(st.maxAbsDifference, diff);
        st.sumAbsDifference += diff;
        // Outside: no point of the bound lies in the sampled interval.
        st.outsideInterval +=
            diff > channels::kStdErrQuantile95 * double(planes.stderr_[i]) + answer.halfWidth;
    } else {
        planes.V[i] = v;
        planes.stderr_[i] = 0.0f;
    }
}

}  // namespace

ExactPenumbraStats exactPenumbraPass(const ExactScene& exact, const SurfaceBuffer& sb,
                                     const AreaLight& light, const ExactPenumbraOptions& options,
                                     const ExactPenumbraPlanes& planes, Progress* progress,
                                     const MeshFacing* facing) {
    SO_CHECK(options.method != PenumbraMethod::Sampled);
    SO_CHECK(light.kind != nullptr);
    SO_CHECK((planes.bound != nullptr) == light.kind->bounded());
    // Its own pixels only with Exact, which writes the planes the sampled pass would have.
    SO_CHECK(planes.spp || (options.method == PenumbraMethod::Exact && planes.cosine));
    const auto t0 = Clock::now();
    ExactPenumbraStats st;
    st.method = options.method;
    st.allPixels = options.allPixels;
    st.errorKind = exactErrorKind(light.type);
    st.bound = options.bound;
    const size_t pixels = size_t(sb.width) * size_t(sb.height);
    std::fill(planes.exactMask, planes.exactMask + pixels, 0.0f);
    if (planes.bound) std::fill(planes.bound, planes.bound + pixels, 0.0f);
    if (options.method == PenumbraMethod::Both)
        std::copy(planes.V, planes.V + pixels, planes.Vexact);
    const std::vector<PixelAnswer> all =
        answers(exact, sb, light, options, planes, progress, facing);
    // Slot order, one thread: the sums are the same at any thread count.
    if (planes.needsSampling) planes.needsSampling->assign(sb.slotCount(), 0);
    for (size_t s = 0; s < all.size(); ++s) {
        if (!all[s].asked) continue;
        st.candidatesTotal += all[s].result.candidates;
        st.backFacesTotal += all[s].result.backFaces;
        const size_t i = sb.pixelOfSlot(s);
        if (!planes.spp) writeCosine(light, sb, s, i, planes);
        apply(all[s], s, i, options, planes, st);
    }
    st.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return st;
}

}  // namespace so
