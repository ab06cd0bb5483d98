#include "cli/trace_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli/output.h"
#include "cli/progress_bar.h"
#include "cli/sequence_frames.h"
#include "core/error.h"
#include "core/gbuffer.h"
#include "core/scene_pose.h"
#include "oracle/exact_penumbra.h"
#include "oracle/oracle_cache.h"
#include "oracle/points.h"

namespace so {

namespace {

// What the penumbrae cost, and what a tighter target would (docs/oracle.md, cost curve).
void printOracleCost(const OracleStats& stats) {
    for (const OracleLightStats& l : stats.lights) {
        if (!l.area || !l.area->targetError) continue;
        const AreaShadowStats& a = *l.area;
        // The exact pass gave the light's pixels (sampled only where it gave no answer).
        if (a.exact && a.exact->method == PenumbraMethod::Exact && a.exact->notApplied.empty()) {
            std::cout << "  " << l.name << ": exact, " << a.exact->pixelsExact << " pixels in "
                      << a.exact->seconds << " s; " << a.pixelsSampled << " sampled\n";
            continue;
        }
        std::cout << "  " << l.name << ": target " << *a.targetError << " took " << a.seconds
                  << " s (mean " << a.sppMean() << " spp)";
        const double tighter = *a.targetError / 2.0;
        if (const std::optional<double> t = a.predictedSeconds(tighter))
            std::cout << "; --target-error " << tighter << " would take about " << *t
                      << " s (half-width ~ samples^" << *a.costSlope() << " on this run)";
        std::cout << "\n";
    }
}

// With --verify: one line on what was checked; exit code 3 (and a line on stderr) on any
// disagreement, else 0.
int reportVerification(const OracleStats& stats, const std::string& scenePath,
                       const std::filesystem::path& jsonPath) {
    if (!stats.verify || stats.verify->lights.empty()) return 0;
    const OracleVerifyStats& verify = *stats.verify;
    const uint64_t bad = verify.disagreements();
    uint64_t checked = 0, ambiguous = 0;
    for (const LightVerification& l : verify.lights) checked += l.checked, ambiguous += l.ambiguous;
    std::cout << "verified " << checked << " pixels against an independent exact re-trace: " << bad
              << " disagreements, " << ambiguous << " within the tolerance (" << verify.seconds()
              << " s)\n";
    if (!bad) return 0;
    std::cerr << "error: " << scenePath << ": verify: " << bad
              << " pixels where the oracle disagrees with the exact re-trace (listed in "
              << jsonPath.string() << ", verify.lights[].pixels)\n";
    return 3;
}

// --tile, checked before the scene is loaded.
std::optional<TileSpec> tileOf(const TraceCommandOptions& options) {
    if (options.tile.empty()) return std::nullopt;
    const TileSpec tile = parseTileSpec(options.tile);
    if (options.oracle.verify.pixels > 0)
        throwInputError("command line", "--tile",
                        "cannot be used with --verify (verify the merged image's scene without "
                        "--tile)");
    return tile;
}

// Every band must hold at least one row of 4x4 tiles of the image.
void checkTileFits(const TileSpec& tile, const CameraDesc& cam) {
    if (tile.count > tileRowCount(cam.height))
        throwInputError("command line", "--tile",
                        std::to_string(tile.count) + " bands is more than the " +
                            std::to_string(tileRowCount(cam.height)) +
                            " rows of 4x4 pixel tiles of an image " + std::to_string(cam.height) +
                            " pixels high");
}

}  // namespace

TileSpec parseTileSpec(const std::string& text) {
    // Digits only, so "-1/4", "+1/4", " 1/4" and "1/4x" are all refused.
    const auto number = [&](const std::string& part) {
        if (part.empty() || part.size() > 4 ||
            part.find_first_not_of("0123456789") != std::string::npos)
            throwInputError("command line", "--tile",
                            "\"" + printable(text, 40) + "\" is not I/N (e.g. 0/4)");
        return std::stoi(part);
    };
    const size_t slash = text.find('/');
    if (slash == std::string::npos)
        throwInputError("command line", "--tile",
                        "\"" + printable(text, 40) + "\" is not I/N (e.g. 0/4)");
    const TileSpec t{number(text.substr(0, slash)), number(text.substr(slash + 1))};
    if (t.count < 1 || t.count > kMaxTiles)
        throwInputError(
            "command line", "--tile",
            "N must be 1 to " + std::to_string(kMaxTiles) + ", not " + std::to_string(t.count));
    if (t.index >= t.count)
        throwInputError("command line", "--tile",
                        "I must be 0 to N - 1 = " + std::to_string(t.count - 1) + ", not " +
                            std::to_string(t.index));
    return t;
}

namespace {

// trace --points: the oracle at a G-buffer's points (docs/external.md, "Points in"). Everything is
// read and checked before the output folder is made.
int runTracePoints(const TraceCommandOptions& options) {
    using Clock = std::chrono::steady_clock;
    if (!options.tile.empty())
        throwInputError("command line", "--tile", "cannot be used with --points");
    if (options.oracle.width > 0 || options.oracle.height > 0)
        throwInputError("command line", "--width/--height",
                        "cannot be used with --points (the image is the G-buffer's size)");
    auto t0 = Clock::now();
    const GBuffer gbuffer = readGBuffer(options.pointsPath);
    Scene scene = loadScene(options.scenePath);
    const double loadSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    printSceneWarnings(options.scenePath, scene);

    const std::filesystem::path out = makeOutputDir(options.outDir, "--out");
    ProgressBar bar(options.progress);
    OracleOptions oracle = options.oracle;
    oracle.progress = bar.callback();
    OracleResult result =
        namingFlag("verify", "--verify", [&] { return runOracleAtPoints(scene, gbuffer, oracle); });
    const OraclePointsStats& points = *result.points;

    TraceOutputOptions output{options.scenePath, loadSeconds,     options.previews,
                              std::nullopt,      oracle.progress, std::nullopt};
    const TraceOutputFiles files = writeTraceOutput(out, scene, oracle, result, output);

    std::cout << "traced " << options.scenePath << " at the points of " << options.pointsPath
              << " (" << gbuffer.width << "x" << gbuffer.height << ": " << points.replayed
              << " replayed exactly, " << points.snapped << " snapped, " << points.offSurface
              << " off surface, " << points.background << " background)\n"
              << "  " << files.exr.string() << "\n  " << files.json.string() << "\n";
    for (const std::string& p : files.previews) std::cout << "  " << p << "\n";
    if (points.offSurface)
        std::cerr << "warning: " << options.pointsPath << ": " << points.offSurface
                  << " covered pixels lie farther than the snap tolerance from every surface of "
                  << options.scenePath << " (no oracle result: A = 0, points.status = 3)\n";
    printOracleCost(result.stats);
    return reportVerification(result.stats, options.scenePath, files.json);
}

}  // namespace

namespace {

// One trace of `scene` (the file's, or one frame of its sequence) into `outDir`.
int traceScene(const TraceCommandOptions& options, const std::optional<TileSpec>& tile,
               const Scene& scene, double loadSeconds, const std::string& outDir,
               const std::optional<SequenceFrame>& frame = std::nullopt) {
    if (scene.stats.degenerateTriangles)
        std::cerr << "warning: " << options.scenePath << ": " << scene.stats.degenerateTriangles
                  << " degenerate (zero-area) triangles (kept, they cannot be hit)\n";

    const CameraDesc cam = effectiveCamera(scene, options.oracle);
    LoadLimits limits;
    if (cam.width > limits.maxImageSide || cam.height > limits.maxImageSide ||
        uint64_t(cam.width) * uint64_t(cam.height) > limits.maxImagePixels)
        throwInputError("command line", "--width/--height", "image too large");

    ProgressBar bar(options.progress);
    OracleOptions oracle = options.oracle;
    oracle.progress = bar.callback();
    if (tile) {
        checkTileFits(*tile, cam);
        oracle.rows = tileRows(cam.height, tile->index, tile->count);
    }
    const RowBand rows = oracle.rows.value_or(RowBand{0, cam.height});

    const std::filesystem::path out = makeOutputDir(outDir, "--out");
    OracleResult result =
        namingFlag("verify", "--verify", [&] { return runOracle(scene, oracle); });

    TraceOutputOptions output{options.scenePath, loadSeconds, options.previews, tile,
                              oracle.progress,   frame};
    const TraceOutputFiles files = writeTraceOutput(out, scene, oracle, result, output);

    std::cout << "traced " << options.scenePath << " (" << scene.stats.triangles << " triangles, "
              << cam.width << "x" << cam.height << ", " << scene.lights.size() << " lights"
              << (tile ? ", rows " + std::to_string(rows.begin) + " to " +
                             std::to_string(rows.end - 1) + " (tile " + options.tile + ")"
                       : std::string())
              << ")\n"
              << "  " << files.exr.string() << "\n  " << files.json.string() << "\n";
    for (const std::string& p : files.previews) std::cout << "  " << p << "\n";
    printOracleCost(result.stats);
    return reportVerification(result.stats, options.scenePath, files.json);
}

// --frame K or --frames A:B, checked against the scene's sequence: the first and last frame.
std::pair<int, int> frameRange(const TraceCommandOptions& options, const Scene& scene) {
    if (!options.pointsPath.empty())
        throwInputError("command line", options.frame.empty() ? "--frames" : "--frame",
                        "cannot be used with --points");
    return sequenceFrameRange(scene, options.scenePath, options.frame, options.frames);
}

// --frame / --frames: each frame posed and traced like any scene; the exit code is the worst.
int traceFrames(const TraceCommandOptions& options, const std::optional<TileSpec>& tile,
                const Scene& scene, double loadSeconds) {
    const auto [first, last] = frameRange(options, scene);
    int code = 0;
    for (int k = first; k <= last; ++k) {
        const double t = sequenceTime(*scene.sequence, k);
        std::string outDir = options.outDir;
        if (!options.frames.empty()) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04d", k);
            outDir = (std::filesystem::path(options.outDir) / name).string();
        }
        if (options.progress)
            std::cerr << "frame " << k << " (t = " << t << " s), " << (k - first + 1) << " of "
                      << (last - first + 1) << "\n";
        code = std::max(code, traceScene(options, tile, sceneAtTime(scene, t), loadSeconds, outDir,
                                         SequenceFrame{k, t}));
    }
    return code;
}

}  // namespace

int runTraceCommand(const TraceCommandOptions& options) {
    if (!options.pointsPath.empty() && options.frame.empty() && options.frames.empty())
        return runTracePoints(options);
    using Clock = std::chrono::steady_clock;
    const std::optional<TileSpec> tile = tileOf(options);
    auto t0 = Clock::now();
    Scene scene = loadScene(options.scenePath);
    const double loadSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    printSceneWarnings(options.scenePath, scene);
    if (!options.frame.empty() || !options.frames.empty())
        return traceFrames(options, tile, scene, loadSeconds);
    return traceScene(options, tile, scene, loadSeconds, options.outDir);
}

}  // namespace so
