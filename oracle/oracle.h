// The oracle: ground-truth shadows for a scene (docs/oracle.md). runOracle computes; the trace
// command (cli/trace_command.h) writes the files; oracle_cache.h keeps them for the compare
// command.
#pragma once

#include <optional>

#include "core/image.h"
#include "core/progress.h"
#include "core/scene.h"
#include "oracle/area_shadow.h"
#include "oracle/offset.h"
#include "oracle/oracle_stats.h"
#include "oracle/verify.h"

namespace so {

// Image rows [begin, end).
struct RowBand {
    int begin = 0, end = 0;
    int count() const { return end - begin; }
    bool operator==(const RowBand&) const = default;
};

// Band `index` of `count` bands of an image `height` rows high: the 4x4 pixel tile rows the
// oracle traces (SurfaceBuffer::kTile) split as evenly as they go, so that the bands' boundaries
// are multiples of 4 and a band traces exactly the whole run's packets. Needs 0 <= index < count
// <= tileRowCount(height), else std::invalid_argument.
RowBand tileRows(int height, int index, int count);
int tileRowCount(int height);

struct OracleOptions {
    int width = 0, height = 0;  // 0: the scene camera's size
    // Another camera than the scene's (a frame of compare --frames-path); width and height above
    // still override its size. Part of the oracle cache's key.
    std::optional<CameraDesc> camera;
    int threads = 0;  // 0: all hardware threads
    // Reports each stage (primary rays, each light) and can cancel (core/progress.h); empty:
    // silent.
    ProgressCallback progress;
    AreaSampling area;  // area lights, when the scene asks for "penumbra"
    // Area lights with "penumbra": the exact pass after the sampled one (exact_penumbra.h).
    ExactPenumbraOptions penumbra;
    // Not on the command line: Legacy256Ulp exists only for the tests that show the verifier
    // catches the occluders it missed (oracle/offset.h).
    OffsetPolicy offsetPolicy = OffsetPolicy::ErrorBound;
    VerifyOptions verify;  // --verify N: re-trace N pixels per light independently (verify.h)
    // `trace --tile`: only this band of image rows is traced (tileRows), and the result image
    // holds only those rows. Every pixel is computed exactly as in the whole run. Not with
    // --verify.
    std::optional<RowBand> rows;
};

// What `trace --points` (oracle/points.h) did with the G-buffer's pixels: oracle.json "points".
struct OraclePointsStats {
    std::string file;
    bool replayChannels = false;         // the G-buffer has id.mesh, id.prim, bary.u, bary.v
    std::string coverageChannel;         // "A" or "coverage"
    bool depthChannel = false;           // Z copied through
    uint64_t replayed = 0, snapped = 0;  // covered pixels by route
    uint64_t offSurface = 0;             // covered, but no surface within the snap tolerance
    uint64_t background = 0;             // coverage 0
    uint64_t replayRejected = 0;  // had replay channels that do not fit this scene: snapped instead
    double wsMaxSnapDistance = 0.0;   // the largest |P - snapped point|, world units
    double wsMaxSnapTolerance = 0.0;  // the largest snap tolerance used, world units
};

struct OracleResult {
    ChannelImage image;  // channels as in docs/exr-channels.md; with options.rows, only those rows
    OracleStats stats;   // the oracle.json content that depends on the run (toJson); with
                         // --verify, stats.verify has one LightVerification per light
    std::optional<OraclePointsStats> points;  // runOracleAtPoints (oracle/points.h) only
};

// The camera description actually used (options.camera, else the scene camera, with the
// option's width and height).
CameraDesc effectiveCamera(const Scene& scene, const OracleOptions& options);

// Throws InputError for options the user chose badly, std::invalid_argument for options no
// command makes (rows that are not a tileRows band), EmbreeError when Embree fails (out of memory).
OracleResult runOracle(const Scene& scene, const OracleOptions& options);

}  // namespace so
