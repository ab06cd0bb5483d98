#include "raster_compare/gl/raster_result.h"

namespace so {

nlohmann::json toJson(const GlInfo& gl) {
    return {{"renderer", gl.renderer}, {"version", gl.version}, {"platform", gl.platform}};
}

nlohmann::json toJson(const RasterTimings& t) {
    return {{"frames", t.frames},
            {"warmup_frames", t.warmupFrames},
            {"camera_ms", t.cameraMs},
            {"wall_ms", t.wallMs},
            {"note",
             "median over the timed frames; GL_TIME_ELAPSED queries (on llvmpipe they measure CPU "
             "work)"}};
}

namespace {
nlohmann::json toJson(const RasterLightStats& l) {
    nlohmann::json faces = nlohmann::json::array();
    for (const glm::dmat4& m : l.clipFromWorld) {
        nlohmann::json rows = nlohmann::json::array();
        for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
        faces.push_back(rows);
    }
    nlohmann::json j = {
        {"name", l.name},
        {"type", l.type},
        {"map", l.map},
        {"clip_from_world", faces},
        {"near", l.wsNear},
        {"far", l.wsFar},
        {"fov_y_deg", l.fovYDeg},
        {l.texelSizeIsAbsolute ? "texel_size" : "texel_size_per_unit_depth", l.texelSize}};
    for (const auto& [pass, ms] : l.passMs) j[pass + "_ms"] = ms;
    return j;
}
}  // namespace

nlohmann::json toJson(const RasterStats& s) {
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [k, v] : s.parameters) params[k] = v;
    nlohmann::json lights = nlohmann::json::array();
    for (const RasterLightStats& l : s.lights) lights.push_back(toJson(l));
    return {{"technique", s.technique},
            {"parameters", params},
            {"image", {{"width", s.width}, {"height", s.height}}},
            {"gl", toJson(s.gl)},
            {"lights", lights},
            {"timings", toJson(s.timings)}};
}

}  // namespace so
