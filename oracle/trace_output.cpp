#include "oracle/trace_output.h"

#include <chrono>

#include <OpenEXR/OpenEXRConfig.h>

#include "core/error.h"
#include "core/image_codec.h"
#include "core/json_file.h"
#include "core/png_encode.h"
#include "core/preview.h"
#include "core/process_clock.h"
#include "core/progress.h"
#include "core/tool_info.h"
#include "embree/embree_handles.h"
#include "oracle/oracle_cache.h"
#include "oracle/points.h"

namespace so {

namespace fs = std::filesystem;

nlohmann::json tracedOptionsJson(const OracleOptions& o, const CameraDesc& cam) {
    // Everything that changes a pixel: the sampling, the camera's pose, the offset policy.
    nlohmann::json options = oracleSamplingJson(o, cam);
    options["eye"] = {cam.wsEye.x, cam.wsEye.y, cam.wsEye.z};
    options["target"] = {cam.wsTarget.x, cam.wsTarget.y, cam.wsTarget.z};
    options["up"] = {cam.wsUp.x, cam.wsUp.y, cam.wsUp.z};
    options["vfov_deg"] = cam.vfovDeg;
    options["offset_policy"] =
        o.offsetPolicy == OffsetPolicy::ErrorBound ? "error bound" : "legacy";
    return options;
}

namespace {

// What was traced: the scene and the camera (docs/oracle.md).
nlohmann::json sceneJson(const std::string& scenePath, const Scene& scene) {
    return {{"file", scenePath},
            {"hash", scene.contentHash},
            {"meshes", scene.meshes.size()},
            {"triangles", scene.stats.triangles},
            {"degenerate_triangles", scene.stats.degenerateTriangles},
            {"skipped_primitives", scene.stats.skippedPrimitives},
            {"gltf_extensions_ignored", scene.stats.gltfExtensionsIgnored},
            {"warnings", scene.stats.warnings},
            {"effects", scene.effects},
            {"bounds",
             {{"min", {scene.wsBounds.lo.x, scene.wsBounds.lo.y, scene.wsBounds.lo.z}},
              {"max", {scene.wsBounds.hi.x, scene.wsBounds.hi.y, scene.wsBounds.hi.z}}}}};
}

nlohmann::json cameraJson(const CameraDesc& cam) {
    return {{"eye", {cam.wsEye.x, cam.wsEye.y, cam.wsEye.z}},
            {"target", {cam.wsTarget.x, cam.wsTarget.y, cam.wsTarget.z}},
            {"up", {cam.wsUp.x, cam.wsUp.y, cam.wsUp.z}},
            {"vfov_deg", cam.vfovDeg}};
}

// oracle.json: what was traced (scene, camera, libraries) and the run's stats (docs/oracle.md).
nlohmann::json oracleJson(const TraceOutputOptions& output, const Scene& scene,
                          const CameraDesc& cam, const OracleStats& stats, double writeSeconds) {
    const std::string imageLibrary = loadedImageLibraryVersion();
    nlohmann::json j = {
        {"format_version", kOracleJsonFormatVersion},
        {"tool", toolJson()},
        {"scene", sceneJson(output.scenePath, scene)},
        {"camera", cameraJson(cam)},
        {"libraries",
         {{"embree", EmbreeDevice::version()},
          {"openexr", OPENEXR_VERSION_STRING},
          // The PNG previews' library; null without previews.
          {"png", output.previews ? nlohmann::json(pngLibraryVersion()) : nlohmann::json()},
          // OpenImageIO reads textures (alpha masks); null where none was read, so it never
          // loaded.
          {"openimageio", imageLibrary.empty() ? nlohmann::json() : nlohmann::json(imageLibrary)}}},
    };
    j.update(toJson(stats));
    // Which pose of the sequence this is: frames of one scene share its file and differ here.
    j["sequence_frame"] =
        output.frame ? nlohmann::json{{"index", output.frame->index}, {"t", output.frame->t}}
                     : nlohmann::json();
    j["phases_seconds"]["load"] = output.loadSeconds;
    j["phases_seconds"]["write"] = writeSeconds;
    j["libraries"]["tbb"] = j["tbb"]["version"];
    j.erase("tbb");
    return j;
}

// The "tile" block of a band's oracle.json (docs/oracle.md, "Tiles").
nlohmann::json tileJson(const TileSpec& tile, const RowBand& rows, const OracleOptions& oracle,
                        const CameraDesc& cam) {
    return {{"index", tile.index},
            {"count", tile.count},
            {"rows", {rows.begin, rows.end}},
            {"options", tracedOptionsJson(oracle, cam)}};
}

// The write phase in its parts, and the whole process so far: what the user waits for beyond the
// passes (issue 45: start-up, the previews and the EXR were most of a small exact trace).
void addWritePhases(nlohmann::json& j, double exrSeconds, double writeSeconds) {
    j["phases_seconds"]["write_exr"] = exrSeconds;
    j["phases_seconds"]["write_previews"] = writeSeconds - exrSeconds;
    const double process = processSeconds();
    j["phases_seconds"]["process"] = process >= 0.0 ? nlohmann::json(process) : nlohmann::json();
}

// oracle.exr, with the provenance attributes. A band is a data window inside the full display
// window (core/image.h ExrRows); trace-merge drops the tile attribute, so the merged file's header
// is the whole run's. At a G-buffer's points the image is the whole.
void writeOracleExr(const std::string& path, const Scene& scene, const OracleResult& result,
                    const TraceOutputOptions& output, const RowBand& rows, int fullHeight) {
    ExrAttributes attributes = {{"shadowOracle/sceneHash", scene.contentHash},
                                {"shadowOracle/toolVersion", toolVersionString()}};
    if (output.tile)
        attributes.emplace_back(kTileAttribute, std::to_string(output.tile->index) + "/" +
                                                    std::to_string(output.tile->count));
    Progress progress("writing " + path, result.image.pixelCount(), output.progress);
    if (result.points)
        writeExr(path, result.image, attributes, result.stats.threads, &progress);
    else
        writeExr(path, result.image, attributes, result.stats.threads, &progress,
                 {rows.begin, fullHeight});
}

}  // namespace

TraceOutputFiles writeTraceOutput(const fs::path& dir, const Scene& scene,
                                  const OracleOptions& options, const OracleResult& result,
                                  const TraceOutputOptions& output) {
    using Clock = std::chrono::steady_clock;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throwInputError(dir.string(), "", "cannot create the folder: " + ec.message());
    const CameraDesc cam = effectiveCamera(scene, options);
    const RowBand rows = options.rows.value_or(RowBand{0, cam.height});

    TraceOutputFiles files{dir / "oracle.exr", dir / "oracle.json", {}};
    const auto t0 = Clock::now();
    writeOracleExr(files.exr.string(), scene, result, output, rows, cam.height);
    const double exrSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (output.previews) files.previews = writePreviews(dir, result.image, scene.lights);
    const double writeSeconds = std::chrono::duration<double>(Clock::now() - t0).count();

    nlohmann::json j = oracleJson(output, scene, cam, result.stats, writeSeconds);
    if (result.points) {
        j["camera"] = nullptr;  // no camera: the points are the G-buffer's
        j["points"] = toJson(*result.points);
    }
    if (output.tile) j["tile"] = tileJson(*output.tile, rows, options, cam);
    addWritePhases(j, exrSeconds, writeSeconds);
    writeJsonFile(files.json, j);
    return files;
}

}  // namespace so
