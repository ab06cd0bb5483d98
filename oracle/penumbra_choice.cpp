#include "oracle/penumbra_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "oracle/lights/area_light_kind.h"

namespace so {

namespace {

// The cost model, in processor seconds (all threads summed): the sampled pass's cost per shadow
// ray (a constant and a term in log2 of the scene's triangles, the BVH's depth) and per alpha
// test, and the exact pass's per point, per triangle the pyramid query returned, per shadow that
// reached the union and, for disk and sphere lights, per side of the gathering octagon of each
// point whose contour was integrated (8 a point: the arcs' quadrature is most of its cost).
// Fitted by bench_penumbra_cost (scripts/penumbra-calibration: both passes on all 16 area lights
// of the shipped scenes, the real ones and the bunny at 96 x 72, target 0.01, one thread,
// processor time, median of 3; least squares on relative residuals, non-negative) on 2026-11-28
// on the 2-core machine, refitted after the exact disk pass (issue 55). Residuals: the exact
// pass within 51% on every light, the sampled pass within 64% (truck_town, the dutch ship and the
// bunny cost more a ray than the model says); docs/benchmarks.md has the table. Only ratios
// matter.
constexpr double kSampledSecondsPerRay = 0.0;
constexpr double kSampledSecondsPerRayLevel = 2.73e-9;  // per ray and log2(scene triangles)
constexpr double kSampledSecondsPerAlphaTest = 4.89e-8;
constexpr double kExactSecondsPerPoint = 8.66e-7;
constexpr double kExactSecondsPerCandidate = 0.0;
constexpr double kExactSecondsPerOccluder = 7.28e-7;
constexpr double kExactSecondsPerBoundSide = 1.98e-6;

}  // namespace

PenumbraMethod cheaperPenumbraMethod(double exactSeconds, double sampledSeconds) {
    return exactSeconds <= kPenumbraExactMargin * sampledSeconds ? PenumbraMethod::Exact
                                                                 : PenumbraMethod::Sampled;
}

std::vector<uint8_t> sparseSlots(const SurfaceBuffer& sb, size_t every) {
    std::vector<uint8_t> slots(sb.slotCount(), 0);
    size_t seen = 0;
    for (size_t s = 0; s < sb.slotCount(); ++s)
        if (sb.pixelOfSlot(s) != SIZE_MAX && sb.hit[s]) slots[s] = seen++ % every == 0;
    return slots;
}

PenumbraChoice choosePenumbraMethod(const Accel& accel, const ExactScene* exact,
                                    const PenumbraProbe& probe, const AreaLight& light,
                                    uint32_t stream, const AreaSampling& sampling,
                                    const ExactPenumbraOptions& options, uint64_t imagePoints,
                                    const std::string& notApplied) {
    PenumbraChoice c;
    if (!notApplied.empty() || !exact) {
        c.reason = "the exact pass does not apply: " + notApplied;
        return c;
    }
    const SurfaceBuffer& sb = *probe.sb;
    const size_t pixels = size_t(sb.width) * size_t(sb.height);
    std::vector<float> V(pixels), stderr_(pixels), spp(pixels), cosine(pixels), mask(pixels),
        bound(light.kind->bounded() ? pixels : 0);
    std::vector<uint8_t> slots =
        probe.slots ? *probe.slots : std::vector<uint8_t>(sb.hit.begin(), sb.hit.end());
    for (size_t s = 0; s < slots.size(); ++s)
        c.probePoints += slots[s] && sb.pixelOfSlot(s) != SIZE_MAX && sb.hit[s];
    // The sampled pass to the target on the probe's points: its rays.
    AreaShadowPlanes sampled{V.data(), stderr_.data(), spp.data(), cosine.data(), nullptr};
    sampled.onlySlots = &slots;
    const AreaShadowStats sampledStats =
        traceAreaShadows(accel, sb, light, sampling, stream, sampled, nullptr);
    c.probeRays = sampledStats.raysTraced;
    // The exact pass on the same points: its triangles.
    ExactPenumbraOptions exactOptions = options;
    exactOptions.method = PenumbraMethod::Exact;
    ExactPenumbraPlanes planes;
    planes.V = V.data();
    planes.stderr_ = stderr_.data();
    planes.cosine = cosine.data();
    planes.exactMask = mask.data();
    planes.bound = bound.empty() ? nullptr : bound.data();  // disk and sphere lights
    planes.onlySlots = &slots;
    std::vector<uint8_t> needsSampling;
    planes.needsSampling = &needsSampling;
    const ExactPenumbraStats e =
        exactPenumbraPass(*exact, sb, light, exactOptions, planes, nullptr, probe.facing);
    c.probeCandidates = e.candidatesTotal;
    c.probeOccluders = e.occludersTotal;
    c.probeKeptSampled = e.pixelsTooManyOccluders + e.pixelsAlphaTested;
    c.probeBoundSides = e.boundSidesTotal;
    if (c.probePoints == 0) {
        c.reason = "the probe's points saw nothing of the scene: sampling (nothing to compare)";
        return c;
    }
    // The probe's own estimates decide, so that every band of a tiled trace (the same probe, a
    // different scale) makes the same choice and states the same reason.
    const double depth = std::log2(std::max<double>(double(probe.sceneTriangles), 2.0));
    const double probeSampled =
        double(c.probeRays) * (kSampledSecondsPerRay + depth * kSampledSecondsPerRayLevel) +
        double(sampledStats.alphaTests) * kSampledSecondsPerAlphaTest;
    // The points the exact pass leaves are sampled as well: their share of the sampled cost.
    const double keptShare = double(c.probeKeptSampled) / double(c.probePoints);
    const double probeExact = double(c.probePoints) * kExactSecondsPerPoint +
                              double(c.probeCandidates) * kExactSecondsPerCandidate +
                              double(c.probeOccluders) * kExactSecondsPerOccluder +
                              double(c.probeBoundSides) * kExactSecondsPerBoundSide +
                              keptShare * probeSampled;
    c.chosen = cheaperPenumbraMethod(probeExact, probeSampled);
    const double scale = double(imagePoints) / double(c.probePoints);
    c.sampledSeconds = scale * probeSampled;
    c.exactSeconds = scale * probeExact;
    char text[160];
    std::snprintf(text, sizeof text,
                  "exact estimated at %.3g times the cost of sampling to the target (exact "
                  "unless over %g times)",
                  probeExact / probeSampled, kPenumbraExactMargin);
    c.reason = text;
    return c;
}

}  // namespace so
