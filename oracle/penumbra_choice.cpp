#include "oracle/penumbra_choice.h"

#include <cstdio>

#include "core/error.h"
#include "oracle/lights/area_light_kind.h"

namespace so {

namespace {

// The cost model, in processor seconds (all threads summed): a shadow ray of the sampled pass with
// its share of the estimator, and the exact pass's cost per point, per triangle the pyramid query
// returned and per shadow that reached the union. Fitted to bench_exact_penumbra's whole runs'
// processor seconds (2026-11-26, this repository's shared 2-core machine; docs/benchmarks.md):
// 1.5e-8 to 7.6e-8 s a ray (penumbra_square, soft_chair, the bunny, fixed costs included), and
// the exact pass's three terms within 30% of all three scenes. Only their ratios matter.
constexpr double kSecondsPerRay = 3.0e-8;
constexpr double kExactSecondsPerPoint = 1.0e-6;
constexpr double kExactSecondsPerCandidate = 0.1e-6;
constexpr double kExactSecondsPerOccluder = 1.5e-6;
// Disk and sphere lights: per side of the last polygons each point's bound integrated (their
// doublings before it and the inscribed polygon's integral included). Measured on sphere_light at
// 96 x 72, one thread, --bound-target 1e-6 against 1e-4 (931,392 against 72,352 sides): 0.19
// processor seconds apart, 2.2e-7 s a side (2026-11-26, the shared 2-core machine).
constexpr double kExactSecondsPerBoundSide = 2.2e-7;

std::string seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g s", s);
    return text;
}

}  // namespace

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
    c.probeRays = traceAreaShadows(accel, sb, light, sampling, stream, sampled, nullptr).raysTraced;
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
    const double scale = double(imagePoints) / double(c.probePoints);
    // The points the exact pass leaves are sampled as well: their share of the sampled rays.
    const double keptShare = double(c.probeKeptSampled) / double(c.probePoints);
    c.sampledSeconds = scale * double(c.probeRays) * kSecondsPerRay;
    c.exactSeconds = scale * (double(c.probePoints) * kExactSecondsPerPoint +
                              double(c.probeCandidates) * kExactSecondsPerCandidate +
                              double(c.probeOccluders) * kExactSecondsPerOccluder +
                              double(c.probeBoundSides) * kExactSecondsPerBoundSide) +
                     keptShare * c.sampledSeconds;
    c.chosen = c.exactSeconds < c.sampledSeconds ? PenumbraMethod::Exact : PenumbraMethod::Sampled;
    c.reason = "estimated " + seconds(c.exactSeconds) + " exact against " +
               seconds(c.sampledSeconds) + " sampled to the target (processor seconds)";
    return c;
}

}  // namespace so
