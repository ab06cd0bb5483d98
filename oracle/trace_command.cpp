#include "oracle/trace_command.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <OpenEXR/OpenEXRConfig.h>
#include <png.h>

#include "core/channels.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/version.h"
#include "oracle/embree_handles.h"

namespace so {

void writeShadowPreview(const std::string& path, const ChannelImage& image,
                        const std::string& light) {
    const float* A = image.channel(channels::kHit);
    const float* V = image.channel(channels::lightChannel(light, channels::kVisibility));
    const float* C = image.channel(channels::lightChannel(light, channels::kCosine));
    std::vector<float> rgb(image.pixelCount() * 3);
    for (size_t i = 0; i < image.pixelCount(); ++i) {
        float r, g, b;
        if (A[i] == 0.0f) {
            r = 0.05f, g = 0.06f, b = 0.09f;  // background
        } else {
            float lit = 0.85f * std::max(C[i], 0.0f) * V[i];
            r = g = b = 0.08f + 0.8f * lit;
        }
        rgb[3 * i] = r;
        rgb[3 * i + 1] = g;
        rgb[3 * i + 2] = b;
    }
    writePngRgb(path, image.width(), image.height(), rgb);
}

int runTraceCommand(const TraceCommandOptions& options) {
    using Clock = std::chrono::steady_clock;
    auto t0 = Clock::now();
    Scene scene = loadScene(options.scenePath);
    const double loadSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    for (const std::string& w : scene.stats.warnings)
        std::cerr << "warning: " << options.scenePath << ": " << w << "\n";
    if (scene.stats.degenerateTriangles)
        std::cerr << "warning: " << options.scenePath << ": " << scene.stats.degenerateTriangles
                  << " degenerate (zero-area) triangles (kept, they cannot be hit)\n";

    const CameraDesc cam = effectiveCamera(scene, options.oracle);
    LoadLimits limits;
    if (cam.width > limits.maxImageSide || cam.height > limits.maxImageSide ||
        uint64_t(cam.width) * uint64_t(cam.height) > limits.maxImagePixels)
        throwInputError("command line", "--width/--height", "image too large");

    std::error_code ec;
    std::filesystem::create_directories(options.outDir, ec);
    if (ec) throwInputError(options.outDir, "--out", "cannot create the folder: " + ec.message());

    OracleResult result = runOracle(scene, options.oracle);

    t0 = Clock::now();
    const std::filesystem::path out(options.outDir);
    const std::string exrPath = (out / "oracle.exr").string();
    {
        Progress progress("writing " + exrPath, result.image.pixelCount(), options.oracle.progress);
        writeExr(exrPath, result.image,
                 {{"shadowOracle/sceneHash", scene.contentHash},
                  {"shadowOracle/toolVersion", std::string(kToolVersion) + " " + kGitRevision}},
                 result.stats["threads"].get<int>(), &progress);
    }
    std::vector<std::string> previews;
    for (const Light& light : scene.lights) {
        std::string png = (out / (light.name + ".png")).string();
        writeShadowPreview(png, result.image, light.name);
        previews.push_back(png);
    }
    const double writeSeconds = std::chrono::duration<double>(Clock::now() - t0).count();

    nlohmann::json j = {
        {"format_version", 2},
        {"tool",
         {{"name", "shadow-oracle"}, {"version", kToolVersion}, {"git_revision", kGitRevision}}},
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
          {"libpng", PNG_LIBPNG_VER_STRING}}},
    };
    j.update(result.stats);
    j["phases_seconds"]["load"] = loadSeconds;
    j["phases_seconds"]["write"] = writeSeconds;
    j["libraries"]["tbb"] = j["tbb"]["version"];
    j.erase("tbb");
    std::ofstream(out / "oracle.json") << j.dump(2) << "\n";

    std::cout << "traced " << options.scenePath << " (" << scene.stats.triangles << " triangles, "
              << cam.width << "x" << cam.height << ", " << scene.lights.size() << " lights)\n"
              << "  " << exrPath << "\n  " << (out / "oracle.json").string() << "\n";
    for (const std::string& p : previews) std::cout << "  " << p << "\n";
    if (!result.verification.empty()) {
        const uint64_t bad = disagreementCount(result.verification);
        uint64_t checked = 0, ambiguous = 0;
        for (const LightVerification& l : result.verification)
            checked += l.checked, ambiguous += l.ambiguous;
        std::cout << "verified " << checked
                  << " pixels against an independent exact re-trace: " << bad << " disagreements, "
                  << ambiguous << " within the tolerance ("
                  << result.stats["phases_seconds"]["verify"].get<double>() << " s)\n";
        if (bad) {
            std::cerr << "error: " << options.scenePath << ": verify: " << bad
                      << " pixels where the oracle disagrees with the exact re-trace (listed in "
                      << (out / "oracle.json").string() << ", verify.lights[].pixels)\n";
            return 3;
        }
    }
    return 0;
}

}  // namespace so
