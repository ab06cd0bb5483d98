// The oracle at a renderer's own surface points (`trace --points`, docs/external.md "Points in"):
// the SurfaceBuffer is built from a G-buffer instead of from primary rays, then the unchanged
// shadow passes run on it. One result per pixel of the G-buffer, so no camera convention has to
// match.
//
// Each covered pixel takes one of two routes:
//   replayed: the G-buffer carries id.mesh, id.prim, bary.u, bary.v that are valid for this scene
//     (ids in range, barycentrics finite and inside the triangle within kReplayBaryTolerance, and
//     the rebuilt point within the snap tolerance of P). The point is rebuilt exactly as
//     tracePrimary does, the geometric normal oriented to agree with N: the oracle's own
//     gbuffer.exr then gives bit for bit the SurfaceBuffer of a plain trace, hence the same V.
//   snapped: the surface P lies on is found by two short rays from P along +N and -N, each
//     snapTolerance(P) long; the nearer hit wins (the +N ray on a tie). The point is rebuilt from
//     that hit's barycentrics on the double triangle and leaves with the usual error-bound offset
//     (offset.h), so self-shadowing is decided on the true surface, not on the rounded P.
//   Neither ray hits: "off surface", no oracle result (A = 0, points.status = 3), counted.
#pragma once

#include <cstdint>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"
#include "oracle/accel.h"
#include "oracle/oracle.h"
#include "oracle/surface_buffer.h"

namespace so {

// points.status values (core/channels.h kPointsStatus).
enum class PointStatus : uint8_t { Background = 0, Replayed = 1, Snapped = 2, OffSurface = 3 };

// The snap tolerance, in local units (core/local_frame.h: the scene's half-extent is in [0.5, 1)):
// kSnapLsAbs plus kSnapUlps float spacings of P's largest world coordinate (P is float32 in the
// file), converted to local units.
inline constexpr double kSnapLsAbs = 1.0 / 65536.0;  // 2^-16: about 1.5e-5 to 3e-5 of the extent
inline constexpr double kSnapUlps = 16.0;
// Barycentrics may stray this far outside the triangle and still replay.
inline constexpr double kReplayBaryTolerance = 1.0 / 1048576.0;  // 2^-20

double snapTolerance(const LocalFrame& frame, const glm::dvec3& wsP);

struct PointsSurface {
    SurfaceBuffer sb;             // lsEye empty; wsDepth the G-buffer's Z, NaN without one
    std::vector<uint8_t> status;  // PointStatus per pixel, row-major
    OraclePointsStats stats;
};

// Builds the SurfaceBuffer from the G-buffer's points (call inside the caller's tbb::task_arena).
// Thread-count independent. A plane whose size is not width x height is std::invalid_argument.
PointsSurface surfaceFromPoints(const Scene& scene, const Accel& accel, const GBuffer& gbuffer,
                                OffsetPolicy offsetPolicy = OffsetPolicy::ErrorBound);

// The oracle at the G-buffer's points: the image is the G-buffer's size and carries the geometry
// channels (P, N rebuilt on the surface; Z the G-buffer's, NaN without one), points.status, and
// every light's channels as runOracle. options.width/height/camera/rows must be unset; --verify
// re-traces the shadow rays (the primary-ray check is skipped: there is no camera). result.points
// holds the counts. The library entry point for `compare --points` as well as `trace --points`.
// Defined in oracle.cpp, beside runOracle, whose setup and shadow passes it shares.
OracleResult runOracleAtPoints(const Scene& scene, const GBuffer& gbuffer,
                               const OracleOptions& options);

nlohmann::json toJson(const OraclePointsStats& stats);

}  // namespace so
