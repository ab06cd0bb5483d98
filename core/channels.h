// The one place that names EXR channels (docs/exr-channels.md). Both the oracle and the raster
// path write through these names, so a comparison can read either file by the same names.
#pragma once

#include <string>
#include <vector>

namespace so::channels {

inline constexpr const char* kHit = "A";  // 1 where the primary ray hit, else 0
inline constexpr const char* kPX = "P.X";
inline constexpr const char* kPY = "P.Y";
inline constexpr const char* kPZ = "P.Z";
inline constexpr const char* kNX = "N.X";
inline constexpr const char* kNY = "N.Y";
inline constexpr const char* kNZ = "N.Z";
inline constexpr const char* kDepth = "Z";  // distance from the eye along the ray, world units
inline constexpr const char* kMeshId = "id.mesh";
inline constexpr const char* kPrimId = "id.prim";
// Embree's barycentrics of the primary hit on triangle (id.mesh, id.prim): gbuffer.exr's exact
// replay channels, read by `trace --points` (docs/external.md).
inline constexpr const char* kBaryU = "bary.u";
inline constexpr const char* kBaryV = "bary.v";
// trace --points: how each pixel was placed (docs/exr-channels.md): 0 background, 1 replayed
// exactly, 2 snapped to the nearest surface, 3 off every surface (no oracle result).
inline constexpr const char* kPointsStatus = "points.status";
// The G-buffer coverage channels trace --points accepts, in the order they are looked for.
inline constexpr const char* kCoverage = "coverage";

// Per-light channel suffixes: "<light name>.<suffix>".
inline constexpr const char* kVisibility = "V";
inline constexpr const char* kCosine = "cos";
inline constexpr const char* kStdErr = "stderr";  // sampled area lights
// A sampled pixel's 95% interval is V +- kStdErrQuantile95 * stderr, clamped to [0, 1]: the
// Student-t quantile for the 7 degrees of freedom of the oracle's 8 replicas (docs/oracle.md).
inline constexpr double kStdErrQuantile95 = 2.3646242515927849;
inline constexpr const char* kSpp = "spp";  // sampled area lights
// --penumbra exact or both (docs/exr-channels.md): 1 where the exact pass gave V, else 0; and with
// both, the exact V beside the sampled one (the sampled V where the exact pass did not apply).
inline constexpr const char* kExact = "exact";
inline constexpr const char* kVisibilityExact = "V_exact";
// Disk and sphere lights with --penumbra exact or both: the half-width of the guaranteed interval
// about the exact pass's V (V_exact with both) where `exact` is 1, else 0.
inline constexpr const char* kBound = "bound";
inline constexpr const char* kUnconverged = "unconverged";  // adaptive: budget spent, target missed
inline constexpr const char* kOccluderDistance = "occ_dist";        // the contact effect
inline constexpr const char* kPredictedAliasing = "aliasing_pred";  // raster.exr only
// raster.exr, shadow-map techniques with a depth map (docs/exr-channels.md): what the pixel's own
// depth comparison saw, in world units: the depth the map held at the receiver's own texel, the
// receiver's own light-space depth, one map texel's size there; and, where a screen-space pass
// filters V afterwards (blur), the V of the comparison itself.
inline constexpr const char* kMapDepth = "map_depth";
inline constexpr const char* kReceiverDepth = "receiver_depth";
inline constexpr const char* kMapTexel = "map_texel";
inline constexpr const char* kVisibilityUnfiltered = "V_unfiltered";

std::string lightChannel(const std::string& lightName, const char* suffix);

// The per-pixel geometry channels every output carries, in a fixed order.
const std::vector<std::string>& geometryChannels();

// A light name must be usable as an EXR layer: 1 to 64 characters from [A-Za-z0-9_-], starting
// with a letter or '_', and not one of the layer names the geometry channels use ("P", "N", "id").
bool isValidLayerName(const std::string& name);

// For names that come from glTF files: replaces invalid characters with '_', prefixes reserved or
// empty names, and truncates. The result passes isValidLayerName.
std::string sanitizeLayerName(const std::string& name, const std::string& fallback);

}  // namespace so::channels
