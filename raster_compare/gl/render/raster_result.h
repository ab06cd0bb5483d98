// What a raster render returns: the image (docs/exr-channels.md) and typed statistics. JSON is
// made only where raster.json and metrics.json are written (toJson).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/timing.h"
#include "core/work_counts.h"
#include "raster_compare/gl/params.h"

namespace so {

struct GlInfo {
    std::string renderer, version, platform;
};

// GL_ARB_pipeline_statistics_query's counts of a pass, as the driver reports them. llvmpipe counts
// fragment shader invocations 16 to each 4 x 4 block of pixels a triangle touches, whatever the
// depth test does (docs/metrics.md, "Work"): WorkCounts::fragments is the exact count.
struct PipelineCounts {
    uint64_t verticesSubmitted = 0, primitivesSubmitted = 0, vertexShaderInvocations = 0,
             fragmentShaderInvocations = 0, clippingInputPrimitives = 0,
             clippingOutputPrimitives = 0;
    PipelineCounts& operator+=(const PipelineCounts& o);
};

// A pass's work in the counted frame: the counts, bytes_moved's three parts and the pipeline's.
struct PassWork {
    WorkCounts counts;
    uint64_t tapBytes = 0, targetBytesRead = 0, targetBytesWritten = 0;
    std::optional<PipelineCounts> pipeline;  // none where the driver lacks the queries
    PassWork& operator+=(const PassWork& o);
};

// One light's family, camera and map, its passes and their times.
struct RasterLightStats {
    std::string name, type;           // the light's name and type
    std::string family;               // the technique's family (TechniqueInfo::family)
    std::vector<std::string> passes;  // the passes that ran for the light, in order
    // Shadow maps: "orthographic", "perspective" or "cube"; empty for families without a map (the
    // map's fields below are then left out of raster.json).
    std::string map;
    std::vector<glm::dmat4> clipFromWorld;  // per map face
    double wsNear = 0.0, wsFar = 0.0, fovYDeg = 0.0;
    // Orthographic maps: the world size of one texel; perspective and cube maps: per unit of
    // depth along the view axis.
    bool texelSizeIsAbsolute = false;
    double texelSize = 0.0;
    // GL time per pass over the timed frames, by pass name ("shadow_map", "visibility").
    std::map<std::string, TimingStats> passMs;
    // GL memory the technique holds for this light (maps, moment and blur targets, the light's
    // visibility target), estimated from the formats and sizes it allocates.
    uint64_t memoryBytes = 0;
    // The family's own counts (shadow volumes: volume triangles, stencil fill), by name.
    std::map<std::string, int64_t> counts;
    // Techniques that precompute before the first frame (lightmaps): the light's bake, which no
    // frame time includes: its wall time (GL finished) and its passes' times, by name
    // ("bake.shadow_map", ...). Absent for every other technique.
    std::optional<double> bakeMs;
    std::map<std::string, double> bakePassMs;
    // The counted frame's work by pass (empty when the render counted none), and its sum.
    std::map<std::string, PassWork> workByPass;
    std::optional<PassWork> work;
};

struct RasterTimings {
    int frames = 0, warmupFrames = 0;
    TimingStats cameraMs, wallMs;  // over the timed frames
    // How many techniques took turns frame by frame with this one (1: rendered alone).
    int interleavedWith = 1;
};

struct RasterStats {
    std::string technique;
    std::map<std::string, ParamSetting> parameters;  // every parameter, defaults included
    int width = 0, height = 0;
    GlInfo gl;
    std::vector<RasterLightStats> lights;
    RasterTimings timings;
    // The counted frame's camera pass (shared by the lights) and the whole frame: every light's
    // passes and the camera pass. None when the render counted no work.
    std::optional<PassWork> cameraWork, frameWork;
    // A technique that resolves its frames over time (Technique::resolve, a resolve that runs
    // passes): how many frames its V holds, this one included; 0 on a cold start (no history:
    // a single frame, or the first of a sequence). None for a technique whose frames stand alone.
    std::optional<int> historyFrames;
};

struct RasterResult {
    ChannelImage image;  // A, P.*, N.*, Z, id.mesh, id.prim, NAME.V, NAME.aliasing_pred
    RasterStats stats;
};

nlohmann::json toJson(const GlInfo& gl);
// Integers as integers: {"resolution": 2048, "alpha": 1.5}.
nlohmann::json toJson(const std::map<std::string, ParamSetting>& parameters);
nlohmann::json toJson(const RasterTimings& t);
nlohmann::json toJson(const PassWork& w);     // {"fragments", ..., "pipeline": {...}}
nlohmann::json toJson(const RasterStats& s);  // the body of raster.json (docs/cli.md)

}  // namespace so
