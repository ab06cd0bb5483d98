// The one list of artifact classes (docs/metrics.md): the error EXRs' layer names, the metric each
// class feeds, its colour in the error maps and its legend text all come from here.
#pragma once

#include <array>
#include <cstddef>

namespace so {

// In the order of precedence: a wrong pixel that several classes explain is drawn (and counted by
// the error map) as the first of them; a wrong pixel that none of the named classes explains is
// "other" (docs/metrics.md). Ghosting comes first: on a pixel whose truth has just changed, a
// history that has not caught up explains a wrong pixel before any cause a single frame has. It
// is only ever set where the caller says where the truth changed (MetricOptions::truthChanged).
enum class Artifact {
    Ghosting,
    PeterPanning,
    LightBleeding,
    PenumbraSpread,
    Acne,
    ScreenBleed,
    Aliasing,
    Penumbra,
    OtherFalseShadow,
    OtherFalseLit
};
inline constexpr size_t kArtifactCount = 10;

struct ArtifactClass {
    Artifact id;
    const char* layer;   // error EXR channel "<light>.<layer>" (docs/exr-channels.md)
    const char* metric;  // its metric in metrics.json (docs/metrics.md)
    const char* legend;  // the report's name for it
    // Its colour in the report's error maps: Okabe-Ito's seven (colour-blind safe), and white for
    // the eighth, which has no hue to confuse; Okabe-Ito's own eighth, black, would vanish on the
    // dimmed truth the maps draw beneath. The ninth, screen-space bleed, is magenta: far brighter
    // than the reddish purple of peter-panning for every colour vision, and apart from white.
    // The tenth, ghosting (compare --sequence only), is cyan: the lightest hue left, well above
    // sky blue's lightness (0.79 against 0.64 in Rec. 709 luma), so that it stays apart from it
    // where the hue alone would not.
    float rgb[3];
};

inline constexpr std::array<ArtifactClass, kArtifactCount> kArtifactClasses = {{
    {Artifact::Ghosting, "ghosting", "sequence.ghosting_rate", "ghosting", {0.0f, 1.0f, 1.0f}},
    {Artifact::PeterPanning,
     "peter_panning",
     "peter_panning_rate",
     "peter-panning",
     {0.80f, 0.47f, 0.65f}},
    {Artifact::LightBleeding,
     "bleeding",
     "light_bleeding_rate",
     "light bleeding",
     {0.34f, 0.71f, 0.91f}},
    {Artifact::PenumbraSpread,
     "penumbra_spread",
     "penumbra_spread_rate",
     "penumbra too wide/shifted",
     {1.0f, 1.0f, 1.0f}},
    {Artifact::Acne, "acne", "acne_rate", "acne", {0.84f, 0.37f, 0.0f}},
    {Artifact::ScreenBleed,
     "screen_bleed",
     "screen_bleed_rate",
     "screen-space bleed",
     {1.0f, 0.0f, 1.0f}},
    {Artifact::Aliasing, "aliasing", "aliasing_rate", "aliasing", {0.94f, 0.89f, 0.26f}},
    {Artifact::Penumbra, "penumbra", "penumbra_mae", "penumbra", {0.0f, 0.45f, 0.70f}},
    {Artifact::OtherFalseShadow,
     "other_false_shadow",
     "other_false_shadow_rate",
     "other false shadow",
     {0.90f, 0.62f, 0.0f}},
    {Artifact::OtherFalseLit,
     "other_false_lit",
     "other_false_lit_rate",
     "other false lit",
     {0.0f, 0.62f, 0.45f}},
}};

inline constexpr const ArtifactClass& artifactClass(Artifact a) {
    return kArtifactClasses[size_t(a)];
}

// The error EXRs' channel of the per-pixel error (docs/metrics.md, mae).
inline constexpr const char* kErrorLayer = "error";

}  // namespace so
