// shadow-oracle as a library: the public C++ API (docs/api.md). Load or build a scene, trace the
// oracle's ground truth, render a built-in technique through the GL path, compare renders and
// renderers' images against the oracle, and read and write the EXR contract
// (docs/exr-channels.md). The same numbers as the `shadow-oracle` command, which is built on the
// same libraries.
//
// Only standard C++ types cross this interface; the implementation (Embree, OpenGL, OpenEXR) stays
// behind it. Every function either returns its result or throws shadow_oracle::Error (or Cancelled)
// with a one-line message: nothing here ends the process or writes to the terminal. Functions are
// safe to call from several threads at once, and each gives what it gives alone: each call uses
// its own threads (TraceOptions::threads) without changing process-wide state, and each render or
// compare its own GL context (renders in several threads run at once; the frame times they
// measure then include each other's load).
//
// find_package(ShadowOracle CONFIG REQUIRED)
// target_link_libraries(app PRIVATE ShadowOracle::shadow_oracle)
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#define SHADOW_ORACLE_API __attribute__((visibility("default")))

namespace shadow_oracle {

// This header's version: a change that breaks a caller raises it (docs/api.md).
inline constexpr int kApiVersion = 4;
// "<tool version> <git revision>", as in every file the tool writes.
SHADOW_ORACLE_API std::string version();

// Bad input (a scene file, an option, an image) or a failure of the machinery (no GL, Embree out
// of memory): what() is one line, the same as the command line prints, e.g.
// "scenes/x.json: lights[0].type: unknown light type "laser" (valid: ...)".
class SHADOW_ORACLE_API Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A progress callback returned false: the computation stopped and returned nothing.
class SHADOW_ORACLE_API Cancelled : public Error {
  public:
    Cancelled() : Error("cancelled") {}
};

struct ProgressUpdate {
    std::string stage;  // "primary rays", "shadow rays sun", "camera path frames"
    uint64_t done = 0, total = 0;
};
// Called from worker threads, one call at a time per stage, at most every 50 ms and once when a
// stage completes. Return false to cancel: the call throws Cancelled soon after.
using ProgressCallback = std::function<bool(const ProgressUpdate&)>;

// Float planes by EXR channel name (docs/exr-channels.md), row 0 at the top, width * height each.
struct SHADOW_ORACLE_API Image {
    int width = 0, height = 0;
    std::vector<std::string> names;
    std::vector<std::vector<float>> planes;  // planes[i] is channel names[i]

    bool has(const std::string& name) const;
    // Throws Error naming the channel and the ones there are.
    const std::vector<float>& channel(const std::string& name) const;
    // A new channel (a plane of `fill`); throws Error if the name is taken.
    std::vector<float>& add(const std::string& name, float fill = 0.0f);
};

// Any EXR the tool writes or reads (every channel as float). Throws Error on a bad file.
SHADOW_ORACLE_API Image readExr(const std::string& path);
// 32-bit float channels, ZIP-compressed, deterministic bytes; `attributes` as string attributes.
SHADOW_ORACLE_API void writeExr(const std::string& path, const Image& image,
                                const std::map<std::string, std::string>& attributes = {});

// A triangle mesh in world space: x, y, z per vertex; three vertex indices per triangle.
struct Mesh {
    std::string name;
    std::vector<double> positions;
    std::vector<uint32_t> triangles;
};

struct LightInfo {
    std::string name, type;  // type: point, directional, spot, rect, disk, sphere, polygon
    bool area = false;       // rect, disk, sphere, polygon: a penumbra (with "penumbra")
};

// A loaded scene: immutable, cheap to copy (shared), usable from several threads at once.
class SHADOW_ORACLE_API Scene {
  public:
    // A scene file (.json, docs/scene-format.md) or a bare .gltf / .glb.
    static Scene load(const std::string& path);
    // Meshes in memory and `description`: a scene file's JSON without "scene_format" and
    // "geometry" (its "camera", "camera_path", "lights" and "effects", checked the same way).
    static Scene fromMeshes(const std::vector<Mesh>& meshes, const std::string& description);

    std::string path() const;  // as given; empty for a scene made in memory
    std::string hash() const;  // of the content (files, or description and meshes)
    std::vector<LightInfo> lights() const;
    std::vector<std::string> effects() const;
    std::pair<int, int> cameraSize() const;  // the scene camera's width and height
    uint64_t triangles() const;
    std::vector<std::string> warnings() const;  // what the loader said, one line each
    // An animated scene's sequence (scene_format 5, docs/scene-format.md "Sequence"): its frame
    // count (0 without a sequence) and frames per second (0 without).
    int frames() const;
    double fps() const;
    // The scene posed at frame k of its sequence (t = k / fps): meshes, lights and camera where
    // the animations and paths put them, a still scene of its own (trace, render, compare and the
    // writers take it as any; oracle.json records the frame). An Error naming "frame" where k is
    // outside [0, frames()) or the scene has no sequence.
    Scene atFrame(int k) const;

    struct Data;  // the implementation's
    const Data& data() const { return *data_; }

  private:
    explicit Scene(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
    std::shared_ptr<const Data> data_;
};

// The `trace` command's options (docs/cli.md, "Trace options": names, defaults and ranges, the
// same as traceOptionsJson() lists). A value out of range is an Error naming the field.
struct TraceOptions {
    int width = 0, height = 0;  // 0: the scene camera's
    int threads = 0;            // 0: all cores
    // Area lights (the "penumbra" effect): stop a pixel when its 95% half-width is below
    // targetError; fixedSpp > 0 takes exactly that many samples instead.
    double targetError = 0.01, agreementTarget = 0.01;
    int maxSpp = 16384, fixedSpp = 0;
    uint32_t seed = 0;
    int verify = 0;  // > 0: re-trace this many pixels per light independently (docs/oracle.md)
    // Area lights (docs/oracle.md, "Exact penumbrae"; disk and sphere lights bounded to 1e-6):
    // "auto" (per light, exact or sampled, whichever a probe estimates cheaper), "sampled",
    // "exact" (every pixel) or "both"; with "both", the exact pass at "penumbra" pixels (their
    // samples disagree) or "all" sampled ones.
    std::string penumbra = "auto", exactPixels = "penumbra";
    // A renderer's G-buffer EXR (docs/external.md, "Points in"): the oracle at its points, at its
    // size, instead of the camera's pixels.
    std::string points;
    ProgressCallback progress;
    // Disk and sphere lights with penumbra "exact", "both" or "auto": the stated error above which
    // a pixel counts as missing its target, and the most sides (a power of two) of the polygons
    // that bound the disk in the independent check (`trace --bound-target`, `--bound-max-sides`).
    double boundTarget = 1e-6;
    int boundMaxSides = 4096;
};

// Every trace option with its command-line name, its key here (the Python keyword, the sweep
// spec's key), type, default, range and the surfaces that take it: `shadow-oracle trace-options
// --json` (format_version 1).
SHADOW_ORACLE_API std::string traceOptionsJson();

struct LightStats {
    std::string name, type;
    double seconds = 0.0;
    uint64_t shadowRays = 0;
    uint64_t unconvergedPixels = 0;  // area lights: pixels that stopped above targetError
};

// The oracle's result. `image` holds oracle.exr's channels (A, P.*, N.*, Z, id.*, and per light
// NAME.V, NAME.cos, with NAME.stderr, NAME.spp on area lights); `statsJson` holds oracle.json's
// statistics of the run under the same keys (lights, shadow_rays, phases_seconds, ...). Pass the
// whole result to compare().
struct TraceResult {
    Image image;
    std::vector<LightStats> lights;
    double seconds = 0.0;        // BVH, primary and shadow rays
    uint64_t disagreements = 0;  // with verify > 0: pixels where the re-trace disagreed
    std::string statsJson;

    struct Data;  // what compare() needs beyond the image
    std::shared_ptr<const Data> data;
};

SHADOW_ORACLE_API TraceResult trace(const Scene& scene, const TraceOptions& options = {});

// `shadow-oracle export` (docs/export.md): outDir (created if missing) gets scene.glb (the scene
// in world space with its camera and KHR_lights_punctual lights), scene.scene.json (a scene file
// loading it), view.json and gbuffer.exr, for the view at width x height (0: the scene camera's).
// Returns the glb's path.
SHADOW_ORACLE_API std::string exportScene(const Scene& scene, const std::string& outDir,
                                          int width = 0, int height = 0, int threads = 0);

// A technique's settings, as on the command line: "kernel" -> "5", "pattern" -> "poisson".
using Parameters = std::vector<std::pair<std::string, std::string>>;

struct RenderOptions {
    int width = 0, height = 0;   // 0: the scene camera's
    int frames = 9, warmup = 2;  // timed frames (their median is frameMs) after untimed ones
    // As `raster --converge N`: N still frames rendered in order with one temporal state, the
    // last returned, resolved (a technique with temporal=on, a ray-traced denoiser); 0 or 1: one
    // frame, a cold start (raster.json's history_frames says which, docs/techniques.md#resolve).
    int converge = 0;
};

struct RenderResult {
    Image image;                        // raster.exr's channels (NAME.V per light and the geometry)
    double frameMs = 0.0;               // median over the timed frames
    std::string statsJson;              // raster.json: passes, times, memory per light
    std::vector<std::string> warnings;  // the GL driver's, settings' deprecations; a line each

    struct Data;  // what writeRenderOutput writes: the image as rendered, the typed stats
    std::shared_ptr<const Data> data;
};

// Every technique and its parameters: `shadow-oracle techniques --json` (docs/techniques.md).
SHADOW_ORACLE_API std::string techniquesJson();
// A technique through the GL path (OpenGL 4.5, headless EGL); throws Error when no GL is there.
SHADOW_ORACLE_API RenderResult render(const Scene& scene, const std::string& technique,
                                      const Parameters& parameters = {},
                                      const RenderOptions& options = {});

// A renderer's shadow visibility judged like a technique (docs/external.md, "Images in").
struct ExternalImage {
    std::string label;
    // The file readImage read it from (what metrics.json and raster.json name); empty for an
    // image made in memory, named `image "LABEL"` there.
    std::string path;
    // Per light of the scene, in its order: V in [0, 1] (1e-3 beyond is clamped, farther is an
    // error), the oracle's width * height each, row 0 at the top.
    std::vector<std::vector<float>> visibility;
    // What it cost, when known (absent: unknown, never 0).
    std::string renderer;
    std::optional<double> frameMs, shadowMs;
    std::optional<uint64_t> memoryBytes;
};
// An image file as `compare --image` reads it: EXR (NAME.V per light, or V/Y/R for one light) or
// a grey PNG (encoding "linear" or "srgb"), with its cost file PATH.json when there is one.
SHADOW_ORACLE_API ExternalImage readImage(const Scene& scene, const std::string& label,
                                          const std::string& path, int width, int height,
                                          const std::string& encoding = "linear");

struct CompareOptions {
    std::vector<std::string> techniques;  // "pcf:kernel=5", as `compare --technique`
    std::vector<ExternalImage> images;
    int boundaryRadius = 2;                  // r of docs/metrics.md
    double contactThresholdRelative = 0.01;  // of the scene's bounding-box diagonal
    int frames = 9, warmup = 2;              // the techniques' timed and untimed frames
    // Stage "techniques", one step per technique rendered; can cancel between techniques.
    ProgressCallback progress;
};

// One light of one row: every metric of metrics.json by its public name (docs/metrics.md:
// "mae", "boundary_displacement_px.p95", "cost.frame_ms", ...), in its order; none where the
// metric does not apply (null in metrics.json). Flags are 0 or 1.
struct SHADOW_ORACLE_API LightMetrics {
    std::string light;
    std::vector<std::pair<std::string, std::optional<double>>> values;
    std::optional<double> get(const std::string& name) const;  // throws Error for an unknown name
};

struct ComparedRow {
    std::string label;
    std::string source;     // "technique" or "external"
    std::string technique;  // the technique's name, or "external"
    std::string family;
    std::vector<LightMetrics> lights;
    Image image;   // what was judged (raster.exr)
    Image errors;  // per light NAME.<artifact class> and NAME.error (compare's error EXR)
};

struct CompareResult {
    std::vector<ComparedRow> rows;      // the techniques in order, then the images
    std::string metricsJson;            // metrics.json, as the compare command writes it
    std::vector<std::string> warnings;  // the GL driver's, settings' deprecations; a line each

    struct Data;  // what writeCompareOutput needs beyond the metrics
    std::shared_ptr<const Data> data;
};

// Throws Error when a technique or parameter is unknown, a label is used twice, or an image does
// not fit the scene's lights and the oracle's size.
SHADOW_ORACLE_API CompareResult compare(const Scene& scene, const TraceResult& oracle,
                                        const CompareOptions& options);

// The command line's output folders, written from the results above (docs/api.md, "Writing the
// command's files"): the files `trace-merge`, `gate`, `index` and a sweep read. outDir is created
// if missing. Each returns the paths it wrote. For the same inputs the bytes are the command's,
// but for what the file says was measured (times, dates) and where the command names its
// arguments differently.

// `trace`'s folder: oracle.exr, oracle.json and (previews) NAME.png per light.
SHADOW_ORACLE_API std::vector<std::string> writeTraceOutput(const Scene& scene,
                                                            const TraceResult& result,
                                                            const std::string& outDir,
                                                            bool previews = true);
// `raster`'s folder: raster.exr, raster.json and (previews) NAME.png per light.
SHADOW_ORACLE_API std::vector<std::string> writeRenderOutput(const Scene& scene,
                                                             const RenderResult& result,
                                                             const std::string& outDir,
                                                             bool previews = true);
// `compare`'s folder: metrics.json, metrics.csv, metrics_wide.csv, a folder per row with
// raster.json and raster.exr, error_LABEL.exr, and (report) report.html with oracle.exr.
// `oracle` is the trace the comparison was made against.
SHADOW_ORACLE_API std::vector<std::string> writeCompareOutput(const Scene& scene,
                                                              const TraceResult& oracle,
                                                              const CompareResult& result,
                                                              const std::string& outDir,
                                                              bool report = true);

}  // namespace shadow_oracle
