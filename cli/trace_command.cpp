#include "cli/trace_command.h"

#include <chrono>
#include <filesystem>
#include <iostream>

#include <OpenEXR/OpenEXRConfig.h>

#include "cli/output.h"
#include "core/error.h"
#include "core/image_codec.h"
#include "core/progress.h"
#include "oracle/embree_handles.h"

namespace so {

namespace {

// oracle.json: what was traced (scene, camera, libraries) and the run's stats (docs/oracle.md).
nlohmann::json oracleJson(const TraceCommandOptions& options, const Scene& scene,
                          const CameraDesc& cam, const OracleStats& stats, double loadSeconds,
                          double writeSeconds) {
    nlohmann::json j = {
        {"format_version", 7},
        {"tool", toolJson()},
        {"scene",
         {{"file", options.scenePath},
          {"hash", scene.contentHash},
          {"meshes", scene.meshes.size()},
          {"triangles", scene.stats.triangles},
          {"degenerate_triangles", scene.stats.degenerateTriangles},
          {"skipped_primitives", scene.stats.skippedPrimitives},
          {"warnings", scene.stats.warnings},
          {"effects", scene.effects},
          {"bounds",
           {{"min", {scene.wsBounds.lo.x, scene.wsBounds.lo.y, scene.wsBounds.lo.z}},
            {"max", {scene.wsBounds.hi.x, scene.wsBounds.hi.y, scene.wsBounds.hi.z}}}}}},
        {"camera",
         {{"eye", {cam.wsEye.x, cam.wsEye.y, cam.wsEye.z}},
          {"target", {cam.wsTarget.x, cam.wsTarget.y, cam.wsTarget.z}},
          {"up", {cam.wsUp.x, cam.wsUp.y, cam.wsUp.z}},
          {"vfov_deg", cam.vfovDeg}}},
        {"libraries",
         {{"embree", EmbreeDevice::version()},
          {"openexr", OPENEXR_VERSION_STRING},
          {"openimageio", imageLibraryVersion()}}},
    };
    j.update(toJson(stats));
    j["phases_seconds"]["load"] = loadSeconds;
    j["phases_seconds"]["write"] = writeSeconds;
    j["libraries"]["tbb"] = j["tbb"]["version"];
    j.erase("tbb");
    return j;
}

// What the penumbrae cost, and what a tighter target would (docs/oracle.md, cost curve).
void printOracleCost(const OracleStats& stats) {
    for (const OracleLightStats& l : stats.lights) {
        if (!l.area || !l.area->targetError) continue;
        const OracleAreaStats& a = *l.area;
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

}  // namespace

int runTraceCommand(const TraceCommandOptions& options) {
    using Clock = std::chrono::steady_clock;
    auto t0 = Clock::now();
    Scene scene = loadScene(options.scenePath);
    const double loadSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    printSceneWarnings(options.scenePath, scene);
    if (scene.stats.degenerateTriangles)
        std::cerr << "warning: " << options.scenePath << ": " << scene.stats.degenerateTriangles
                  << " degenerate (zero-area) triangles (kept, they cannot be hit)\n";

    const CameraDesc cam = effectiveCamera(scene, options.oracle);
    LoadLimits limits;
    if (cam.width > limits.maxImageSide || cam.height > limits.maxImageSide ||
        uint64_t(cam.width) * uint64_t(cam.height) > limits.maxImagePixels)
        throwInputError("command line", "--width/--height", "image too large");

    const std::filesystem::path out = makeOutputDir(options.outDir);
    OracleResult result = runOracle(scene, options.oracle);

    t0 = Clock::now();
    const std::string exrPath = (out / "oracle.exr").string();
    {
        Progress progress("writing " + exrPath, result.image.pixelCount(), options.oracle.progress);
        writeExr(exrPath, result.image,
                 {{"shadowOracle/sceneHash", scene.contentHash},
                  {"shadowOracle/toolVersion", toolVersionString()}},
                 result.stats.threads, &progress);
    }
    const std::vector<std::string> previews = writePreviews(out, result.image, scene.lights);
    const double writeSeconds = std::chrono::duration<double>(Clock::now() - t0).count();

    const std::filesystem::path jsonPath = out / "oracle.json";
    writeJsonFile(jsonPath,
                  oracleJson(options, scene, cam, result.stats, loadSeconds, writeSeconds));

    std::cout << "traced " << options.scenePath << " (" << scene.stats.triangles << " triangles, "
              << cam.width << "x" << cam.height << ", " << scene.lights.size() << " lights)\n"
              << "  " << exrPath << "\n  " << jsonPath.string() << "\n";
    for (const std::string& p : previews) std::cout << "  " << p << "\n";
    printOracleCost(result.stats);
    return reportVerification(result.stats, options.scenePath, jsonPath);
}

}  // namespace so
