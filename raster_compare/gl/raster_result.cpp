#include "raster_compare/gl/raster_result.h"

namespace so {

namespace {
void addTiming(nlohmann::json& j, const std::string& key, const TimingStats& t) {
    j[key + "_ms"] = t.median;
    j[key + "_ms_p25"] = t.p25;
    j[key + "_ms_p75"] = t.p75;
}
}  // namespace

nlohmann::json toJson(const GlInfo& gl) {
    return {{"renderer", gl.renderer}, {"version", gl.version}, {"platform", gl.platform}};
}

nlohmann::json toJson(const std::map<std::string, ParamSetting>& parameters) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, p] : parameters)
        j[name] = p.integer ? nlohmann::json(int64_t(p.value)) : nlohmann::json(p.value);
    return j;
}

nlohmann::json toJson(const RasterTimings& t) {
    nlohmann::json j = {
        {"frames", t.frames},
        {"warmup_frames", t.warmupFrames},
        {"interleaved_with", t.interleavedWith},
        {"note",
         "median and quartiles over the timed frames, the techniques of one run taking turns frame "
         "by frame; GL_TIME_ELAPSED queries (on llvmpipe, a CPU rasterizer, they measure CPU "
         "work)"}};
    addTiming(j, "camera", t.cameraMs);
    addTiming(j, "wall", t.wallMs);
    return j;
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
        {"name", l.name}, {"type", l.type}, {"family", l.family}, {"passes", l.passes}};
    if (!l.map.empty()) {
        j["map"] = l.map;
        j["clip_from_world"] = faces;
        j["near"] = l.wsNear;
        j["far"] = l.wsFar;
        j["fov_y_deg"] = l.fovYDeg;
        j[l.texelSizeIsAbsolute ? "texel_size" : "texel_size_per_unit_depth"] = l.texelSize;
    }
    for (const auto& [pass, t] : l.passMs) addTiming(j, pass, t);
    j["memory_bytes"] = l.memoryBytes;
    if (!l.counts.empty()) j["counts"] = l.counts;
    if (l.bakeMs) {
        j["bake_ms"] = *l.bakeMs;
        j["bake_passes_ms"] = l.bakePassMs;
    }
    return j;
}
}  // namespace

nlohmann::json toJson(const RasterStats& s) {
    nlohmann::json lights = nlohmann::json::array();
    for (const RasterLightStats& l : s.lights) lights.push_back(toJson(l));
    return {{"technique", s.technique},
            {"parameters", toJson(s.parameters)},
            {"image", {{"width", s.width}, {"height", s.height}}},
            {"gl", toJson(s.gl)},
            {"lights", lights},
            {"timings", toJson(s.timings)}};
}

}  // namespace so
