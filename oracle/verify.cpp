#include "oracle/verify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/lights/light_kind.h"
#include "oracle/area_shadow.h"
#include "oracle/disk_bounds.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/offset.h"
#include "oracle/reference_light.h"

namespace so {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Below this |cos| (or cone / emitter test value) the reference calls a facing test a tie: the
// oracle decides it on float normals and points (error ~1e-7).
constexpr double kCosTie = 1e-6;

uint64_t mix(uint64_t a, uint64_t b) {
    SplitMix m{a * 0x100000001B3ull ^ b};
    return m.next();
}

// Two-sided standard normal quantile: z with P(|Z| > z) = alpha, by bisection on erfc.
double normalQuantileTwoSided(double alpha) {
    double lo = 0.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (std::erfc(mid / std::numbers::sqrt2) > alpha ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// The regularized incomplete beta function I_x(a, b) by its continued fraction (Lentz), for x
// below (a + 1) / (a + b + 2), where it converges quickly: the tails the verifier asks for.
double incompleteBetaTail(double x, double a, double b) {
    if (x <= 0.0) return 0.0;
    const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) +
                                  a * std::log(x) + b * std::log1p(-x)) /
                         a;
    constexpr double kTiny = 1e-300;
    double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
    d = 1.0 / (std::fabs(d) < kTiny ? kTiny : d);
    double f = d;
    for (int m = 1; m <= 500; ++m) {
        for (int odd = 0; odd < 2; ++odd) {
            const double num = odd ? -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))
                                   : m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
            d = 1.0 + num * d;
            d = 1.0 / (std::fabs(d) < kTiny ? kTiny : d);
            c = 1.0 + num / c;
            if (std::fabs(c) < kTiny) c = kTiny;
            f *= c * d;
        }
        if (std::fabs(c * d - 1.0) < 1e-15) break;
    }
    return front * f;
}

}  // namespace

double studentTwoSidedP(double t, double dof) {
    if (!(dof < 1e7)) return std::erfc(std::fabs(t) / std::numbers::sqrt2);
    const double x = dof / (dof + t * t);
    // P(|T| > t) = I_x(dof / 2, 1 / 2); past the continued fraction's fast range use the
    // complement (only for small t, where the tail is large and nothing cancels badly).
    if (x < (dof / 2.0 + 1.0) / (dof / 2.0 + 2.5)) return incompleteBetaTail(x, dof / 2.0, 0.5);
    return 1.0 - incompleteBetaTail(1.0 - x, 0.5, dof / 2.0);
}

double studentQuantileTwoSided(double alpha, double dof) {
    double lo = 0.0, hi = 1e6;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (studentTwoSidedP(mid, dof) > alpha ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

namespace {

// The light seen from p as the hard-shadow pass sees it (area lights: a point at the centre).
struct HardTarget {
    glm::dvec3 dir{0.0};
    double tMax = kInf;
};

}  // namespace

// The reference's view of one pixel: its own primary hit.
struct Verifier::PixelRef {
    glm::dvec3 p{0.0}, n{0.0};  // hit point on the double triangle, normal facing the eye
    TriangleId id;
    double lsPointGap = 0.0;  // |oracle's hit point - p|: the primary hit's own uncertainty
};

Verifier::Verifier(const Scene& scene, const LocalFrame& frame, const Camera* camera,
                   const VerifyOptions& options, uint32_t seed)
    : exact_(scene, frame),
      frame_(frame),
      camera_(camera ? std::optional<Camera>(*camera) : std::nullopt),
      options_(options),
      seed_(seed),
      oracleQuantile95_(studentQuantileTwoSided(0.05, options.oracleDof)) {}

std::vector<size_t> Verifier::choosePixels(const Light& light, uint32_t lightIndex,
                                           const SurfaceBuffer& sb, uint64_t& random,
                                           uint64_t& nearHorizon) const {
    // Candidates: pixels with a primary hit (slots), in slot order; near-horizon ones apart.
    const double sinHorizon = std::sin(options_.horizonDeg * std::numbers::pi / 180.0);
    const glm::dvec3 lsLight = frame_.lsFromWs(light.wsPosition);
    std::vector<size_t> hits, horizon;
    for (size_t s = 0; s < sb.slotCount(); ++s) {
        if (sb.pixelOfSlot(s) == SIZE_MAX || !sb.hit[s]) continue;
        hits.push_back(s);
        const glm::dvec3 p(sb.lsPoint(s)), n(sb.lsNormal(s));
        const glm::dvec3 toLight =
            isDirectional(light) ? -light.wsDirection : glm::normalize(lsLight - p);
        if (std::fabs(glm::dot(n, toLight)) < sinHorizon) horizon.push_back(s);
    }
    // A partial Fisher-Yates shuffle with the seed: the same pixels at any thread count.
    SplitMix rng{mix(mix(seed_, lightIndex), 0x7665726966ull)};
    auto pick = [&](std::vector<size_t>& from, size_t count) {
        count = std::min(count, from.size());
        for (size_t i = 0; i < count; ++i)
            std::swap(from[i], from[i + size_t(rng.next() % (from.size() - i))]);
        from.resize(count);
        return from;
    };
    std::vector<size_t> chosen = pick(hits, size_t(options_.pixels));
    random = chosen.size();
    std::sort(chosen.begin(), chosen.end());
    std::vector<size_t> extra;
    for (size_t s : pick(horizon, size_t(options_.pixels)))
        if (!std::binary_search(chosen.begin(), chosen.end(), s)) extra.push_back(s);
    nearHorizon = extra.size();
    chosen.insert(chosen.end(), extra.begin(), extra.end());
    return chosen;
}

// Re-traces the primary ray. Anything but Agree ends the pixel's check: the reference sees a
// different surface (a disagreement unless within the tolerance).
Verifier::Verdict Verifier::primary(int x, int y, const SurfaceBuffer& sb, size_t slot,
                                    PixelRef& ref, VerifyDisagreement& d,
                                    bool& alphaAmbiguous) const {
    if (!camera_) {
        // Points mode: no primary ray. The oracle's triangle and barycentrics on the reference's
        // own double vertices, the normal oriented as the oracle's (which agrees with the
        // G-buffer's N).
        const TriangleId id{sb.meshId[slot], sb.primId[slot]};
        ref.p = exact_.point(id, sb.baryU[slot], sb.baryV[slot]);
        ref.n = exact_.normal(id, glm::dvec3(sb.lsNormal(slot)));
        ref.id = id;
        ref.lsPointGap = glm::length(glm::dvec3(sb.lsPoint(slot)) - ref.p);
        return Verdict::Agree;
    }
    SO_CHECK(sb.lsEye.has_value());
    const glm::dvec3 lsEye = *sb.lsEye;
    const glm::dvec3 dir = camera_->generateRay(x, y).direction;
    // Alpha tests along the primary ray: the float ray may pass the tolerance from this one.
    const ExactTracer::Hit h =
        exact_.tracer().closestHit(lsEye, dir, 0.0, kInf, {}, kTolAbs, kTolPerT);
    const TriangleId oracleId{sb.meshId[slot], sb.primId[slot]};
    if (h.found && sb.hit[slot] && h.id == oracleId) {
        ref.p = exact_.point(h.id, h.b1, h.b2);
        ref.n = exact_.normal(h.id, -dir);
        ref.id = h.id;
        ref.lsPointGap = glm::length(glm::dvec3(sb.lsPoint(slot)) - ref.p);
        return Verdict::Agree;
    }
    // Different surfaces: ambiguous if the ray passes within the tolerance of an edge or a
    // surface on the way to the farther of the two hits, or both hits lie at the same depth
    // (coplanar duplicates: which one is "first" is a tie). The farther hit's own triangle is
    // left out: the segment ends just past it, so it would always be within the tolerance of the
    // end, and whether the nearer hit is robust (crossed well inside its triangle, its alpha test
    // clear) or robustly missed is the question.
    const double tOracle = sb.hit[slot] ? glm::length(glm::dvec3(sb.lsPoint(slot)) - lsEye) : kInf;
    const double tRef = h.found ? h.t : kInf;
    const double tFar = std::max(tOracle, tRef);
    const double tEnd = std::isfinite(tFar) ? tFar * (1.0 + 1e-6) : kInf;
    const TriangleId farId = !std::isfinite(tFar) ? TriangleId{}
                             : tOracle >= tRef    ? oracleId
                                                  : h.id;
    const ExactTracer::SegmentQuery q =
        exact_.tracer().segment(lsEye, dir, tEnd, farId, kTolAbs, kTolPerT);
    alphaAmbiguous = alphaAmbiguous || h.alphaAmbiguous || q.alphaAmbiguous;
    const bool ambiguous = q.ambiguous || h.alphaAmbiguous || q.alphaAmbiguous ||
                           std::fabs(tOracle - tRef) <= kTolAbs + kTolPerT * tRef;
    d.kind = "primary";
    d.oracleV = sb.hit[slot] ? 1.0 : 0.0;
    d.referenceV = h.found ? 1.0 : 0.0;
    d.wsMargin = frame_.wsLength(q.margin);
    d.wsOccluderDist = frame_.wsLength(tRef);
    return ambiguous ? Verdict::Ambiguous : Verdict::Disagree;
}

Verifier::Verdict Verifier::hardPixel(const Light& light, const PixelRef& ref, float oracleV,
                                      VerifyDisagreement& d, bool& alphaAmbiguous) const {
    HardTarget tgt;
    bool reaches = true;  // faces the light, inside its cone, on its emitting side
    const glm::dvec3 lsPos = frame_.lsFromWs(light.wsPosition);
    double tie = kInf;  // the smallest facing/cone/emitter test value: near 0 is a tie
    if (isDirectional(light)) {
        tgt.dir = -light.wsDirection;
    } else {
        const glm::dvec3 w = lsPos - ref.p;
        const double dist = glm::length(w);
        tgt.dir = w / dist;
        // The oracle's segment stops short of the light by twice its end margin (hard_shadow.cpp).
        tgt.tMax = std::max(0.0, dist - 2.0 * double(offsetMargin(glm::vec3(lsPos))));
        if (hasCone(light)) {
            const double cosCone = glm::dot(-tgt.dir, light.wsDirection);
            const double cosOuter = std::cos(light.outerConeDeg * std::numbers::pi / 180.0);
            reaches = reaches && !(cosCone < cosOuter);
            tie = std::min(tie, std::fabs(cosCone - cosOuter));
        }
        if (lightKind(light.type).oneSided()) {
            const double behind = glm::dot(light.wsEmitNormal(), -w) / dist;
            reaches = reaches && behind > 0.0;
            tie = std::min(tie, std::fabs(behind));
        }
    }
    d.cosine = glm::dot(ref.n, tgt.dir);
    reaches = reaches && d.cosine > 0.0;
    tie = std::min(tie, std::fabs(d.cosine));
    d.kind = "shadow";
    d.oracleV = oracleV;
    d.wsOccluderDist = kInf;
    bool ambiguous = tie < kCosTie;
    double refV = 0.0;
    if (reaches) {
        const ExactTracer::SegmentQuery q = exact_.tracer().segment(
            ref.p, tgt.dir, tgt.tMax, ref.id, kTolAbs + ref.lsPointGap, kTolPerT);
        refV = q.occluded ? 0.0 : 1.0;
        ambiguous = ambiguous || q.ambiguous || q.alphaAmbiguous;
        alphaAmbiguous = alphaAmbiguous || q.alphaAmbiguous;
        d.wsMargin = frame_.wsLength(q.margin);
        d.wsOccluderDist = frame_.wsLength(q.firstHitT);
    }
    d.referenceV = refV;
    return double(oracleV) == refV ? Verdict::Agree
           : ambiguous             ? Verdict::Ambiguous
                                   : Verdict::Disagree;
}

Verifier::Verdict Verifier::areaPixel(const Light& light, uint32_t lightIndex, size_t pixel,
                                      const PixelRef& ref, float oracleV, float oracleStderr,
                                      float oracleSpp, float oracleBound, double z,
                                      VerifyDisagreement& d) const {
    const ReferenceLight reference(light, frame_);
    const glm::dvec3 c = frame_.lsFromWs(light.wsPosition);
    SplitMix rng{mix(mix(mix(seed_, lightIndex), pixel), 0x61726561ull)};
    double sw = 0, swv = 0, sw2 = 0, sw2v = 0, maxG = 0;
    uint64_t nonZero = 0;
    for (int i = 0; i < options_.areaSamples; ++i) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        glm::dvec3 y, ny;
        reference.point(u1, u2, y, ny);
        const glm::dvec3 w = y - ref.p;
        const double dist = glm::length(w);
        const glm::dvec3 dir = w / dist;
        const double G =
            std::max(0.0, glm::dot(ref.n, dir)) * std::max(0.0, -glm::dot(ny, dir)) / (dist * dist);
        if (!(G > 0.0)) continue;
        // Stop just short of the light: geometry touching it does not block it (as the oracle).
        const bool blocked = exact_.tracer().occluded(ref.p, dir, 0.0, dist * (1.0 - 1e-7), ref.id);
        const double v = blocked ? 0.0 : 1.0;
        sw += G, swv += G * v, sw2 += G * G, sw2v += G * G * v;
        maxG = std::max(maxG, G);
        ++nonZero;
    }
    d.kind = "area";
    d.oracleV = oracleV;
    d.oracleHalfWidth = kIntervalQuantile95 * double(oracleStderr) + double(oracleBound);
    d.cosine = glm::dot(ref.n, glm::normalize(c - ref.p));
    if (oracleSpp == 0.0f || nonZero == 0) {
        // The oracle skipped the pixel (light below the horizon, behind it) or the reference
        // found no sample with G > 0: compare only where both measured something.
        d.referenceV = nonZero ? swv / sw : 0.0;
        return (oracleSpp == 0.0f) == (nonZero == 0) ? Verdict::Agree : Verdict::Ambiguous;
    }
    // The oracle's ratio estimator and prior (a formula, not a trace): with independent samples
    // its delta-method standard error is honest.
    const RatioEstimate est = ratioEstimate(sw, swv, sw2, sw2v, nonZero);
    d.referenceV = est.V;
    d.referenceHalfWidth = kZ95 * est.stderr_;
    // The oracle states V +- kIntervalQuantile95 * stderr, a Student-t interval with
    // options_.oracleDof degrees of freedom: its standard error is that half-width over the
    // t quantile. The reference's (thousands of independent samples) is as good as known. Their
    // difference over the combined standard error is t-distributed with Welch-Satterthwaite's
    // degrees of freedom, judged at the same tail as the normal z (Bonferroni over the pixels).
    const double seOracle = kIntervalQuantile95 * double(oracleStderr) / oracleQuantile95_;
    const double seRef = est.stderr_;
    const double var = seOracle * seOracle + seRef * seRef;
    const double dofRef = double(nonZero) - 1.0;
    const double welch =
        var * var / (std::pow(seOracle, 4) / options_.oracleDof + std::pow(seRef, 4) / dofRef);
    const double threshold =
        seOracle > 0.0 ? studentQuantileTwoSided(std::erfc(z / std::numbers::sqrt2), welch) : z;
    // Where every reference sample agreed (all blocked, or all lit), the delta method's spread is
    // 0 and only the prior's floor is left, which assumes the lit part is not where G peaks. The
    // test then asks instead whether N uniform samples of the light could all have missed a part
    // of weight share |V_oracle - V_ref|: its area share is at least |dV| * mean G / max G (mean
    // over all N, zeros included), and N samples miss an area share q with probability (1 - q)^N.
    // The largest G seen stands in for the light's (a slight under-estimate). Exact pixels near
    // the horizon on the real chess board needed this: V 0.0046 exact, 0 of 4,096 samples lit.
    double allowed = threshold * std::sqrt(var);
    if (swv == 0.0 || swv == sw) {
        const double n = double(options_.areaSamples);
        const double tail = std::erfc(z / std::numbers::sqrt2);
        const double missable = -std::expm1(std::log(tail) / n);  // 1 - tail^(1/N)
        allowed = std::max(allowed, missable * maxG / (sw / n));
    }
    // A bounded V (stderr 0) is wrong only where the reference lies beyond the bound by more than
    // its own error.
    return std::fabs(double(oracleV) - d.referenceV) <= allowed + double(oracleBound)
               ? Verdict::Agree
               : Verdict::Disagree;
}

// The polygons' bound (disk_bounds.h) as the verifier runs it: a modest target, and the sides
// it may take (a pixel that stops first keeps the wider interval it reached: still sure).
constexpr DiskBoundOptions kVerifyBound{1e-5, 32, 4096};
constexpr uint32_t kVerifyBoundMaxOccluders = 100000;

Verifier::Verdict Verifier::polygonBoundPixel(const Light& light, const SurfaceBuffer& sb,
                                              size_t slot, float oracleV, float oracleBound,
                                              VerifyDisagreement& d) const {
    // The exact pass's own point and normal (exact_penumbra.cpp), not the re-traced ones: the
    // two methods answer the same question.
    const TriangleId id{sb.meshId[slot], sb.primId[slot]};
    const glm::dvec3 p = exact_.point(id, sb.baryU[slot], sb.baryV[slot]);
    const glm::dvec3 n = exact_.normal(id, glm::dvec3(sb.lsNormal(slot)));
    DiskLightShape disk;
    if (!areaLightKind(light.type).boundedDisk(light, frame_, p, disk))
        return Verdict::Agree;  // inside a sphere: no light
    const DiskVisibility b = diskLightVisibility(exact_.tracer(), disk, p, n, id,
                                                 kVerifyBoundMaxOccluders, kVerifyBound);
    if (b.counts.status == PolygonVisibilityStatus::TooManyOccluders ||
        b.counts.status == PolygonVisibilityStatus::AlphaTested)
        return Verdict::Agree;  // no answer to compare (the exact pass gave none there either)
    const bool none = b.counts.status == PolygonVisibilityStatus::NoLight;
    const double lower = none ? 0.0 : b.lower, upper = none ? 0.0 : b.upper;
    // NAME.bound holds the stated error and V's rounding to float, rounded up.
    if (double(oracleV) + double(oracleBound) >= lower &&
        double(oracleV) - double(oracleBound) <= upper)
        return Verdict::Agree;
    d.kind = "area";
    d.oracleV = oracleV;
    d.oracleHalfWidth = oracleBound;
    d.referenceV = 0.5 * (lower + upper);
    d.referenceHalfWidth = 0.5 * (upper - lower);
    return Verdict::Disagree;
}

LightVerification Verifier::verifyLight(const Light& light, uint32_t lightIndex, bool sampled,
                                        const SurfaceBuffer& sb, const float* V,
                                        const float* stderr_, const float* spp, const float* bound,
                                        const float* exact) const {
    const auto t0 = Clock::now();
    LightVerification out;
    out.light = light.name;
    out.sampled = sampled;
    const std::vector<size_t> slots =
        choosePixels(light, lightIndex, sb, out.random, out.nearHorizon);
    out.checked = slots.size();
    out.zThreshold =
        normalQuantileTwoSided(options_.familyAlpha / double(std::max<size_t>(1, slots.size())));
    std::vector<Verdict> verdicts(slots.size(), Verdict::Agree);
    std::vector<VerifyDisagreement> found(slots.size());
    std::vector<uint8_t> primaryDiffers(slots.size(), 0), alphaAmbiguous(slots.size(), 0);
    const bool boundedLight = isAreaLight(light) && areaLightKind(light.type).bounded();
    tbb::parallel_for(size_t(0), slots.size(), [&](size_t i) {
        const size_t slot = slots[i];
        const size_t pixel = sb.pixelOfSlot(slot);
        VerifyDisagreement& d = found[i];
        d.x = int(pixel % size_t(sb.width));
        d.y = int(pixel / size_t(sb.width));
        d.nearHorizon = i >= out.random;
        PixelRef ref;
        bool alpha = false;
        const Verdict seen = primary(d.x, d.y, sb, slot, ref, d, alpha);
        if (seen != Verdict::Agree) {
            primaryDiffers[i] = seen == Verdict::Ambiguous;
            verdicts[i] = seen;
        } else {
            // Area lights: the samples' alpha tests are decided in double, not judged (a sample
            // the float path decides otherwise is one of thousands, inside the intervals).
            verdicts[i] =
                sampled ? areaPixel(light, lightIndex, pixel, ref, V[pixel], stderr_[pixel],
                                    spp[pixel], bound ? bound[pixel] : 0.0f, out.zThreshold, d)
                        : hardPixel(light, ref, V[pixel], d, alpha);
            // An exact pixel of a bounded light (disk, sphere): also against the polygons' bound.
            if (verdicts[i] == Verdict::Agree && sampled && bound && exact &&
                exact[pixel] == 1.0f && boundedLight)
                verdicts[i] = polygonBoundPixel(light, sb, slot, V[pixel], bound[pixel], d);
        }
        alphaAmbiguous[i] = alpha && verdicts[i] == Verdict::Ambiguous;
    });
    for (size_t i = 0; i < slots.size(); ++i) {
        out.agree += verdicts[i] == Verdict::Agree;
        out.ambiguous += verdicts[i] == Verdict::Ambiguous;
        out.primaryDiffers += primaryDiffers[i];
        out.alphaAmbiguous += alphaAmbiguous[i];
        if (verdicts[i] == Verdict::Disagree) {
            ++out.disagree;
            out.disagreements.push_back(found[i]);
        }
    }
    out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return out;
}

uint64_t disagreementCount(const std::vector<LightVerification>& lights) {
    uint64_t n = 0;
    for (const LightVerification& l : lights) n += l.disagree;
    return n;
}

}  // namespace so
