// The one list of artifact classes (docs/metrics.md): the error EXRs' layer names, the metric each
// class feeds, its colour in the error maps and its legend text all come from here.
#pragma once

#include <array>
#include <cstddef>

namespace so {

enum class Artifact { Acne, PeterPanning, Aliasing, LightBleeding, Penumbra };
inline constexpr size_t kArtifactCount = 5;

struct ArtifactClass {
    Artifact id;
    const char* layer;   // error EXR channel "<light>.<layer>" (docs/exr-channels.md)
    const char* metric;  // its metric in metrics.json (docs/metrics.md)
    const char* legend;  // the report's name for it
    float rgb[3];        // its colour in the report's error maps
};

// In the order of the Artifact enum; a later class is drawn over an earlier one.
inline constexpr std::array<ArtifactClass, kArtifactCount> kArtifactClasses = {{
    {Artifact::Acne, "acne", "acne_rate", "acne", {0.9f, 0.1f, 0.1f}},
    {Artifact::PeterPanning,
     "peter_panning",
     "peter_panning_rate",
     "peter-panning",
     {0.9f, 0.1f, 0.9f}},
    {Artifact::Aliasing, "aliasing", "aliasing_rate", "aliasing", {0.95f, 0.85f, 0.1f}},
    {Artifact::LightBleeding,
     "bleeding",
     "light_bleeding_rate",
     "light bleeding",
     {0.1f, 0.85f, 0.9f}},
    {Artifact::Penumbra, "penumbra", "penumbra_mae", "penumbra", {0.2f, 0.35f, 1.0f}},
}};

inline constexpr const ArtifactClass& artifactClass(Artifact a) {
    return kArtifactClasses[size_t(a)];
}

// The error EXRs' channel of the per-pixel error (docs/metrics.md, mae).
inline constexpr const char* kErrorLayer = "error";

}  // namespace so
