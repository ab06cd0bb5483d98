// What a raster render returns: the image (docs/exr-channels.md) and typed statistics. JSON is
// made only where raster.json and metrics.json are written (toJson).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "core/image.h"

namespace so {

struct GlInfo {
    std::string renderer, version, platform;
};

// One light's camera and map, and its passes' times.
struct RasterLightStats {
    std::string name, type;                 // the light's name and type
    std::string map;                        // "orthographic", "perspective" or "cube"
    std::vector<glm::dmat4> clipFromWorld;  // per map face
    double wsNear = 0.0, wsFar = 0.0, fovYDeg = 0.0;
    // Orthographic maps: the world size of one texel; perspective and cube maps: per unit of
    // depth along the view axis.
    bool texelSizeIsAbsolute = false;
    double texelSize = 0.0;
    // Median GL time per pass over the timed frames, by pass name ("shadow_map", "visibility").
    std::map<std::string, double> passMs;
};

struct RasterTimings {
    int frames = 0, warmupFrames = 0;
    double cameraMs = 0.0, wallMs = 0.0;  // medians over the timed frames
};

struct RasterStats {
    std::string technique;
    std::map<std::string, double> parameters;  // every parameter, defaults included
    int width = 0, height = 0;
    GlInfo gl;
    std::vector<RasterLightStats> lights;
    RasterTimings timings;
};

struct RasterResult {
    ChannelImage image;  // A, P.*, N.*, Z, id.mesh, id.prim, NAME.V, NAME.aliasing_pred
    RasterStats stats;
};

nlohmann::json toJson(const GlInfo& gl);
nlohmann::json toJson(const RasterTimings& t);
nlohmann::json toJson(const RasterStats& s);  // the body of raster.json (docs/cli.md)

}  // namespace so
