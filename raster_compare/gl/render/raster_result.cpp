#include "raster_compare/gl/render/raster_result.h"

namespace so {

namespace {
void addTiming(nlohmann::json& j, const std::string& key, const TimingStats& t) {
    j[key + "_ms"] = t.median;
    j[key + "_ms_p25"] = t.p25;
    j[key + "_ms_p75"] = t.p75;
}
}  // namespace

PipelineCounts& PipelineCounts::operator+=(const PipelineCounts& o) {
    verticesSubmitted += o.verticesSubmitted;
    primitivesSubmitted += o.primitivesSubmitted;
    vertexShaderInvocations += o.vertexShaderInvocations;
    fragmentShaderInvocations += o.fragmentShaderInvocations;
    clippingInputPrimitives += o.clippingInputPrimitives;
    clippingOutputPrimitives += o.clippingOutputPrimitives;
    return *this;
}

PassWork& PassWork::operator+=(const PassWork& o) {
    counts += o.counts;
    tapBytes += o.tapBytes;
    targetBytesRead += o.targetBytesRead;
    targetBytesWritten += o.targetBytesWritten;
    if (o.pipeline) {
        if (pipeline)
            *pipeline += *o.pipeline;
        else
            pipeline = o.pipeline;
    }
    return *this;
}

nlohmann::json toJson(const PassWork& w) {
    const WorkCounts& c = w.counts;
    nlohmann::json pipeline;  // null without the queries
    if (const auto& p = w.pipeline)
        pipeline = {{"vertices_submitted", p->verticesSubmitted},
                    {"primitives_submitted", p->primitivesSubmitted},
                    {"vertex_shader_invocations", p->vertexShaderInvocations},
                    {"fragment_shader_invocations", p->fragmentShaderInvocations},
                    {"clipping_input_primitives", p->clippingInputPrimitives},
                    {"clipping_output_primitives", p->clippingOutputPrimitives}};
    return {{"fragments", c.fragments},
            {"texture_taps", c.textureTaps},
            {"texels_written", c.texelsWritten},
            {"bytes_moved", c.bytesMoved},
            {"draw_calls", c.drawCalls},
            {"passes", c.passes},
            {"rays_traced", c.raysTraced},
            {"tap_bytes", w.tapBytes},
            {"target_bytes_read", w.targetBytesRead},
            {"target_bytes_written", w.targetBytesWritten},
            {"pipeline", pipeline}};
}

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
    if (l.work) {
        j["work"] = toJson(*l.work);
        nlohmann::json byPass = nlohmann::json::object();
        for (const auto& [pass, w] : l.workByPass) byPass[pass] = toJson(w);
        j["work_by_pass"] = byPass;
    }
    return j;
}
}  // namespace

nlohmann::json toJson(const RasterStats& s) {
    nlohmann::json lights = nlohmann::json::array();
    for (const RasterLightStats& l : s.lights) lights.push_back(toJson(l));
    nlohmann::json j = {{"technique", s.technique},
                        {"parameters", toJson(s.parameters)},
                        {"image", {{"width", s.width}, {"height", s.height}}},
                        {"gl", toJson(s.gl)},
                        {"lights", lights},
                        {"timings", toJson(s.timings)}};
    if (s.frameWork && s.cameraWork)
        j["work"] = {{"frame", toJson(*s.frameWork)}, {"camera", toJson(*s.cameraWork)}};
    if (s.historyFrames) j["history_frames"] = *s.historyFrames;
    return j;
}

}  // namespace so
