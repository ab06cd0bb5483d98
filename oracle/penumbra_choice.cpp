#include "oracle/penumbra_choice.h"

#include <cstdio>

#include "core/error.h"

namespace so {

namespace {

// The cost model, in processor seconds (all threads summed): the sampled pass's cost per shadow
// ray and per point, and the exact pass's per point, per triangle the pyramid query returned, per
// shadow that reached the union and, for disk and sphere lights, per side of the last polygons
// each point's bound integrated. Fitted by bench_penumbra_cost (scripts/penumbra-calibration: both
// passes on every area light of the shipped scenes, the real ones and the bunny, one thread,
// processor time, median of 3; least squares on relative residuals) on FIT_DATE; the fit, its
// residuals and the choices it makes are in docs/benchmarks.md. Only ratios matter.
constexpr double kSampledSecondsPerRay = 3.0e-8;
constexpr double kSampledSecondsPerPoint = 0.0;
constexpr double kExactSecondsPerPoint = 1.0e-6;
constexpr double kExactSecondsPerCandidate = 0.1e-6;
constexpr double kExactSecondsPerOccluder = 1.5e-6;
constexpr double kExactSecondsPerBoundSide = 2.2e-7;
// Exact wins unless its estimate exceeds sampling's by more than this factor: the fit's
// residuals reach MARGIN_WHY, so closer estimates cannot tell the two apart, and between two
// methods of about the same cost the one without sampling error is the better answer.
constexpr double kExactMargin = 1.0;

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
        bound(light.type == LightType::Rect ? 0 : pixels);
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
    c.sampledSeconds = scale * (double(c.probeRays) * kSampledSecondsPerRay +
                                double(c.probePoints) * kSampledSecondsPerPoint);
    c.exactSeconds = scale * (double(c.probePoints) * kExactSecondsPerPoint +
                              double(c.probeCandidates) * kExactSecondsPerCandidate +
                              double(c.probeOccluders) * kExactSecondsPerOccluder +
                              double(c.probeBoundSides) * kExactSecondsPerBoundSide) +
                     keptShare * c.sampledSeconds;
    c.chosen = c.exactSeconds <= kExactMargin * c.sampledSeconds ? PenumbraMethod::Exact
                                                                 : PenumbraMethod::Sampled;
    char margin[16];
    std::snprintf(margin, sizeof margin, "%g", kExactMargin);
    c.reason = "estimated " + seconds(c.exactSeconds) + " exact against " +
               seconds(c.sampledSeconds) + " sampled to the target (processor seconds; exact " +
               "unless over " + margin + " times sampling)";
    return c;
}

}  // namespace so
