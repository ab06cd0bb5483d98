#include "oracle/exact_penumbra.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/channels.h"
#include "core/error.h"
#include "core/progress.h"
#include "oracle/polygon_visibility.h"

namespace so {

namespace {

// In the enum's order.
constexpr std::array<const char*, 3> kMethodNames = {"sampled", "exact", "both"};

}  // namespace

const char* penumbraMethodName(PenumbraMethod m) {
    return kMethodNames.at(size_t(m));
}

PenumbraMethod parsePenumbraMethod(const std::string& text, const std::string& file,
                                   const std::string& field) {
    for (size_t k = 0; k < kMethodNames.size(); ++k)
        if (text == kMethodNames[k]) return PenumbraMethod(k);
    throwInputError(file, field,
                    "\"" + printable(text, 40) + "\" is not a method (sampled, exact or both)");
}

bool parseExactPixels(const std::string& text, const std::string& file, const std::string& field) {
    if (text == "penumbra" || text == "all") return text == "all";
    throwInputError(file, field, "\"" + printable(text, 40) + "\" is not penumbra or all");
}

std::span<const StatField<ExactPenumbraStats>> ExactPenumbraStats::fields() {
    using S = ExactPenumbraStats;
    static constexpr StatField<S> kFields[] = {
        {"pixels_exact", &S::pixelsExact},
        {"pixels_kept_sampled.too_many_occluders", &S::pixelsTooManyOccluders},
        {"pixels_kept_sampled.alpha_tested", &S::pixelsAlphaTested},
        {"occluders.total", &S::occludersTotal},
        {"occluders.max", &S::occludersMax, Combine::Max},
        {"candidates_total", &S::candidatesTotal},
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
    return type == LightType::Rect ? "exact" : "bound";
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

RectLightShape shapeOf(const AreaLight& light) {
    return {light.dCenter - 0.5 * light.dU - 0.5 * light.dV, light.dU, light.dV, light.dEmitNormal};
}

DiskLightShape diskShapeOf(const AreaLight& light) {
    DiskLightShape disk;
    disk.center = light.dCenter;
    disk.radius = light.dRadius;
    disk.emitNormal = light.dEmitNormal;
    diskAxes(disk.emitNormal, disk.e1, disk.e2);
    return disk;
}

// What one pixel's exact V came to (status Exact, TooManyOccluders or AlphaTested), or nothing
// asked; disk and sphere lights: the bound's half-width and sides too.
struct PixelAnswer {
    bool asked = false;
    PolygonVisibility result;
    double halfWidth = 0.0;
    uint32_t sides = 0;
    bool reachedTarget = true;
};

// The light seen from p, by its type.
PixelAnswer answerAt(const ExactScene& exact, const AreaLight& light,
                     const ExactPenumbraOptions& options, const glm::dvec3& p, const glm::dvec3& n,
                     TriangleId id) {
    PixelAnswer a;
    a.asked = true;
    if (light.type == LightType::Rect) {
        a.result =
            rectLightVisibility(exact.tracer(), shapeOf(light), p, n, id, options.maxOccluders);
        return a;
    }
    DiskLightShape disk;
    if (light.type == LightType::Sphere) {
        const glm::dvec3 w = light.dCenter - p;
        if (!(glm::dot(w, w) > light.dRadius * light.dRadius)) return a;  // inside: NoLight
        disk = sphereSilhouette(light.dCenter, light.dRadius, p);
    } else {
        disk = diskShapeOf(light);
    }
    const DiskVisibility d =
        diskLightVisibility(exact.tracer(), disk, p, n, id, options.maxOccluders, options.bound);
    a.result = d.counts;
    a.halfWidth = d.halfWidth();
    a.sides = d.sides;
    a.reachedTarget = d.reachedTarget;
    return a;
}

bool selected(const ExactPenumbraOptions& options, const ExactPenumbraPlanes& planes, size_t i) {
    if (!(planes.spp[i] > 0.0f)) return false;  // skipped by the sampled pass: V = 0, exactly
    return options.allPixels || (planes.V[i] > 0.0f && planes.V[i] < 1.0f);
}

// The answers per slot, in parallel; nothing shared is written.
std::vector<PixelAnswer> answers(const ExactScene& exact, const SurfaceBuffer& sb,
                                 const AreaLight& light, const ExactPenumbraOptions& options,
                                 const ExactPenumbraPlanes& planes, Progress* progress) {
    std::vector<PixelAnswer> out(sb.slotCount());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sb.slotCount(), 64),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t s = r.begin(); s < r.end(); ++s) {
                              const size_t i = sb.pixelOfSlot(s);
                              if (i == SIZE_MAX || !sb.hit[s] || !selected(options, planes, i))
                                  continue;
                              const TriangleId id{sb.meshId[s], sb.primId[s]};
                              const glm::dvec3 p = exact.point(id, sb.baryU[s], sb.baryV[s]);
                              const glm::dvec3 n = exact.normal(id, glm::dvec3(sb.lsNormal(s)));
                              out[s] = answerAt(exact, light, options, p, n, id);
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
void apply(const PixelAnswer& answer, size_t i, const ExactPenumbraOptions& options,
           const ExactPenumbraPlanes& planes, ExactPenumbraStats& st) {
    const PolygonVisibility& a = answer.result;
    if (a.status == PolygonVisibilityStatus::TooManyOccluders) {
        ++st.pixelsTooManyOccluders;
        return;
    }
    if (a.status == PolygonVisibilityStatus::AlphaTested) {
        ++st.pixelsAlphaTested;
        return;
    }
    ++st.pixelsExact;
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
                                     const ExactPenumbraPlanes& planes, Progress* progress) {
    SO_CHECK(options.method != PenumbraMethod::Sampled);
    SO_CHECK(light.type == LightType::Rect || light.type == LightType::Disk ||
             light.type == LightType::Sphere);
    SO_CHECK((planes.bound != nullptr) == (light.type != LightType::Rect));
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
    const std::vector<PixelAnswer> all = answers(exact, sb, light, options, planes, progress);
    // Slot order, one thread: the sums are the same at any thread count.
    for (size_t s = 0; s < all.size(); ++s) {
        if (!all[s].asked) continue;
        st.candidatesTotal += all[s].result.candidates;
        apply(all[s], sb.pixelOfSlot(s), options, planes, st);
    }
    st.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return st;
}

}  // namespace so
