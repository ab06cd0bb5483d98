#include "raster_compare/gl/lightmaps/lightmap_bake.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "core/lights/light_kind.h"
#include "core/lights/make_light.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/lights/light_samples.h"
#include "raster_compare/gl/lights/raster_light_kind.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"

namespace so {

namespace {

constexpr int kFloatsPerVertex = 8;  // local position, face normal, atlas texel coordinates

// The static triangles in the atlas's space, with the positions and face normals GpuScene
// uploads (so a texel's point is the point the camera's lookup maps to it), then each triangle's
// centroid as a point: drawn after the triangles where no triangle covered a texel's centre, it
// gives every triangle at least the texel that holds its centroid (a triangle smaller than a
// texel, or a sliver, may cover no centre at all, and dilation cannot fill a chart that has no
// texel).
struct AtlasGeometry {
    GlBuffer vbo;
    GlVertexArray vao;
    GLsizei vertices = 0;   // GL_TRIANGLES, from 0
    GLsizei centroids = 0;  // GL_POINTS, after them
};

AtlasGeometry uploadAtlasGeometry(const GpuScene& gpu, const LightmapAtlas& atlas) {
    const Scene& scene = gpu.scene();
    std::vector<float> v, centroids;
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const MeshPrimitive& m = scene.meshes[mi];
        for (size_t t = 0; t < atlas.chartOf[mi].size(); ++t) {
            if (atlas.chartOf[mi][t] < 0) continue;
            glm::dvec3 p[3];
            for (size_t k = 0; k < 3; ++k)
                p[k] = gpu.frame().lsFromWs(m.wsPositions[m.indices[3 * t + k]]);
            const glm::dvec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
            const auto& texel = atlas.corners[mi][t];
            for (size_t k = 0; k < 3; ++k)
                v.insert(v.end(), {float(p[k].x), float(p[k].y), float(p[k].z), float(n.x),
                                   float(n.y), float(n.z), float(texel[k].x), float(texel[k].y)});
            const glm::dvec3 pc = (p[0] + p[1] + p[2]) / 3.0;
            const glm::dvec2 tc = (texel[0] + texel[1] + texel[2]) / 3.0;
            centroids.insert(centroids.end(), {float(pc.x), float(pc.y), float(pc.z), float(n.x),
                                               float(n.y), float(n.z), float(tc.x), float(tc.y)});
        }
    }
    AtlasGeometry g;
    g.vertices = GLsizei(v.size() / kFloatsPerVertex);
    g.centroids = GLsizei(centroids.size() / kFloatsPerVertex);
    v.insert(v.end(), centroids.begin(), centroids.end());
    g.vbo = makeBuffer();
    glNamedBufferStorage(g.vbo.get(), GLsizeiptr(std::max<size_t>(1, v.size()) * sizeof(float)),
                         v.empty() ? nullptr : v.data(), 0);
    g.vao = makeVertexArray();
    glVertexArrayVertexBuffer(g.vao.get(), 0, g.vbo.get(), 0, kFloatsPerVertex * sizeof(float));
    const GLint sizes[3] = {3, 3, 2};
    const GLuint offsets[3] = {0, 3, 6};
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(g.vao.get(), a);
        glVertexArrayAttribFormat(g.vao.get(), a, sizes[a], GL_FLOAT, GL_FALSE,
                                  offsets[a] * sizeof(float));
        glVertexArrayAttribBinding(g.vao.get(), a, 0);
    }
    return g;
}

// An atlas-sized target with its framebuffer (colour attachments in order).
struct Target {
    std::vector<GlTexture> textures;
    GlFramebuffer fbo;
};

Target makeTarget(const std::vector<GLenum>& formats, int width, int height) {
    Target t;
    t.fbo = makeFramebuffer();
    std::vector<GLenum> buffers;
    for (GLenum f : formats) {
        t.textures.push_back(makeTexture2D(f, width, height));
        const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + buffers.size());
        glNamedFramebufferTexture(t.fbo.get(), attachment, t.textures.back().get(), 0);
        buffers.push_back(attachment);
    }
    glNamedFramebufferDrawBuffers(t.fbo.get(), GLsizei(buffers.size()), buffers.data());
    return t;
}

class Baker {
  public:
    Baker(const Light& light, const GpuScene& gpu, const LightmapAtlas& atlas,
          const BakeSettings& settings);
    BakedLightmap run();

  private:
    void createMap();
    void buildPrograms();
    void drawAtlas(GLuint program);
    void texels();
    void sample(const Light& point, const glm::dvec3& wsSample);
    void shadowMap(const LightCamera& lc);
    void resolveAndDilate();
    uint64_t countFilled(GLuint source);
    void fullScreen(GLuint program, GLuint fbo, GLuint source, GLuint geometry = 0);

    const Light& light_;
    const GpuScene& gpu_;
    const LightmapAtlas& atlas_;
    BakeSettings settings_;
    bool areaSampled_;
    PassTimer timer_;
    AtlasGeometry geometry_;
    Target texels_, sampleV_, sums_, ping_, pong_;
    GlTexture depth_;  // which texels the triangles took (0) and the centroids then (0.5)
    GlTexture map_;
    std::vector<GlFramebuffer> mapFbos_;
    GlProgram depthProg_, texelsProg_, visibilityProg_, weightProg_;
    BakedLightmap out_;
};

Baker::Baker(const Light& light, const GpuScene& gpu, const LightmapAtlas& atlas,
             const BakeSettings& settings)
    : light_(light),
      gpu_(gpu),
      atlas_(atlas),
      settings_(settings),
      areaSampled_(isAreaLight(light.type) && gpu.scene().hasEffect("penumbra")) {
    const int W = atlas.width, H = atlas.height;
    geometry_ = uploadAtlasGeometry(gpu, atlas);
    texels_ = makeTarget({GL_RGBA32F, GL_RGBA16F}, W, H);
    sampleV_ = makeTarget({GL_R32F}, W, H);
    sums_ = makeTarget({GL_RG32F}, W, H);
    depth_ = makeTexture2D(GL_DEPTH_COMPONENT16, W, H);
    for (GLuint fbo : {texels_.fbo.get(), sampleV_.fbo.get()})
        glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth_.get(), 0);
    createMap();
    const uint64_t mapTexels = uint64_t(settings.resolution) * uint64_t(settings.resolution);
    out_.peakBytes =
        uint64_t(W) * uint64_t(H) * (16 + 8 + 4 + 8 + 2) + mapTexels * 4 * mapFbos_.size();
    buildPrograms();
}

// The light's shadow maps: one map for its own camera, or a cube for a point light and for each
// sample of an area light (a point light there); 32-bit float depth, read point-sampled.
void Baker::createMap() {
    const bool cube = rasterLightKind(light_.type).cameraKind() == LightCamera::Kind::Cube;
    const int res = settings_.resolution;
    map_ = makeTexture(cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D);
    glTextureStorage2D(map_.get(), 1, GL_DEPTH_COMPONENT32F, res, res);
    for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER})
        glTextureParameteri(map_.get(), p, GL_NEAREST);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(map_.get(), wrap, GL_CLAMP_TO_EDGE);
    for (int f = 0; f < (cube ? 6 : 1); ++f) {
        GlFramebuffer fbo = makeFramebuffer();
        if (cube)
            glNamedFramebufferTextureLayer(fbo.get(), GL_DEPTH_ATTACHMENT, map_.get(), 0, f);
        else
            glNamedFramebufferTexture(fbo.get(), GL_DEPTH_ATTACHMENT, map_.get(), 0);
        glNamedFramebufferDrawBuffer(fbo.get(), GL_NONE);
        mapFbos_.push_back(std::move(fbo));
    }
}

void Baker::buildPrograms() {
    depthProg_ = buildProgram(gpu_.alphaDefines(), shaders::scene_vert,
                              {shaders::alpha_test_glsl, shaders::depth_frag});
    const std::string lightKind = lightCameraDefines(light_);
    texelsProg_ =
        buildProgram(lightKind, shaders::lightmap_bake_vert, {shaders::lightmap_texels_frag});
    // Every sample of an area light is a point light: a cube map, as its kind's camera is.
    const std::string pointKind = lightCameraDefines(light_);
    const SlopeBias bias(parseParams("lightmap", SlopeBias::params(), {}));
    visibilityProg_ = buildProgram(
        "#define ALPHA_TEST_OFF\n#define VISIBILITY_PASS\n#define MAP_DEPTH\n"
        // What one lookup of the 32-bit float depth map reads (the work counts' SO_TAP).
        "#define MAP_TEXEL_BYTES 4\n#define MAP_FILTER_TEXELS 1\n" +
            pointKind + bias.defines(),
        shaders::lightmap_bake_vert,
        // slope-bias's lookup: basic with the slope bias (biases/slope_bias.glsl).
        {shaders::alpha_test_glsl, shaders::shadow_map_frag, shaders::slope_bias_glsl,
         shaders::basic_glsl});
    const std::string emitter = !areaSampled_ ? std::string("#define EMITTER_POINT\n")
                                              : rasterLightKind(light_.type).emitterDefine();
    // What its fetches read (the work counts' SO_TAP): the texels' positions and normals and the
    // sample's V.
    const std::string tapBytes =
        "#define POSITION_TEXEL_BYTES " + std::to_string(texelBytes(texels_.textures[0].get())) +
        "\n#define NORMAL_TEXEL_BYTES " + std::to_string(texelBytes(texels_.textures[1].get())) +
        "\n#define VISIBILITY_TEXEL_BYTES " +
        std::to_string(texelBytes(sampleV_.textures[0].get())) + "\n";
    weightProg_ = buildProgram("#define WEIGHT_PASS\n" + emitter + tapBytes,
                               shaders::fullscreen_vert, {shaders::accumulate_glsl});
    const LocalFrame& frame = gpu_.frame();
    for (GLuint p : {texelsProg_.get(), visibilityProg_.get()})
        glProgramUniform2f(p, glGetUniformLocation(p, "u_atlasSize"), float(atlas_.width),
                           float(atlas_.height));
    setVec3(texelsProg_.get(), "u_lsLightPosition", frame.lsFromWs(light_.wsPosition));
    setVec3(texelsProg_.get(), "u_lsLightDirection", glm::normalize(light_.wsDirection));
    setInt(visibilityProg_.get(), "u_map", 0);
    const GLuint wp = weightProg_.get();
    setVec3(wp, "u_lsLightCenter", frame.lsFromWs(light_.wsPosition));
    if (areaSampled_ && isOneSided(light_)) setVec3(wp, "u_lsEmitNormal", light_.wsEmitNormal());
    setInt(wp, "u_visibility", 0);
    setInt(wp, "u_position", 1);
    setInt(wp, "u_normal", 2);
}

// The triangles, then the centroids where no triangle took the texel (the bound framebuffer has
// depth_: depth 0 for the triangles, 0.5 for the points, the test LESS against a clear of 1), so
// the texels pass and every sample's visibility pass fill the very same texels with the very
// same points.
void Baker::drawAtlas(GLuint program) {
    const float one = 1.0f;
    glDepthMask(GL_TRUE);  // before the clear, which the mask gates (a frame ends with it off)
    glClearBufferfv(GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glViewport(0, 0, atlas_.width, atlas_.height);
    glUseProgram(program);
    glBindVertexArray(geometry_.vao.get());
    setFloat(program, "u_depth", 0.0);
    glDrawArrays(GL_TRIANGLES, 0, geometry_.vertices);
    setFloat(program, "u_depth", 0.5);
    glDrawArrays(GL_POINTS, geometry_.vertices, geometry_.centroids);
    glDisable(GL_DEPTH_TEST);
}

// Each covered texel's point and normal; how many texels the triangles cover, and how many more
// the centroids took.
void Baker::texels() {
    timer_.begin("bake.texels");
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(texels_.fbo.get(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(texels_.fbo.get(), GL_COLOR, 1, zero);
    glBindFramebuffer(GL_FRAMEBUFFER, texels_.fbo.get());
    const GlQuery covered = makeQuery(GL_SAMPLES_PASSED);
    glBeginQuery(GL_SAMPLES_PASSED, covered.get());
    drawAtlas(texelsProg_.get());
    glEndQuery(GL_SAMPLES_PASSED);
    timer_.end();
    GLuint64 all = 0;
    glGetQueryObjectui64v(covered.get(), GL_QUERY_RESULT, &all);
    // The triangles' share: the same pass without the points, counted from the depth written.
    const GlQuery triangles = makeQuery(GL_SAMPLES_PASSED);
    glBeginQuery(GL_SAMPLES_PASSED, triangles.get());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    setFloat(texelsProg_.get(), "u_depth", 0.0);
    glDrawArrays(GL_TRIANGLES, 0, geometry_.vertices);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 byTriangles = 0;
    glGetQueryObjectui64v(triangles.get(), GL_QUERY_RESULT, &byTriangles);
    out_.texelsCovered = byTriangles;
    out_.texelsFromCentroids = all - byTriangles;
}

// The static meshes' depth from the light's camera (alpha-tested ones cut by their masks).
void Baker::shadowMap(const LightCamera& lc) {
    timer_.begin("bake.shadow_map");
    gpu_.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glViewport(0, 0, settings_.resolution, settings_.resolution);
    glUseProgram(depthProg_.get());
    const Scene& scene = gpu_.scene();
    for (int f = 0; f < lc.faces; ++f) {
        const float one = 1.0f;
        glBindFramebuffer(GL_FRAMEBUFFER, mapFbos_[size_t(f)].get());
        glClearNamedFramebufferfv(mapFbos_[size_t(f)].get(), GL_DEPTH, 0, &one);
        setMat4(depthProg_.get(), "u_clipFromLocal", lc.clipFromLocal(f));
        for (size_t m = 0; m < scene.meshes.size(); ++m)
            if (!scene.meshes[m].dynamic) gpu_.drawMesh(depthProg_.get(), m);
    }
    glDisable(GL_DEPTH_TEST);
    timer_.end();
}

// One point of the light: its map, its depth test at every texel, its weighted V into the sums.
void Baker::sample(const Light& point, const glm::dvec3& wsSample) {
    const LocalFrame& frame = gpu_.frame();
    const LightCamera lc = fitLightCamera(point, frame, gpu_.lsBounds(), settings_.resolution);
    shadowMap(lc);
    timer_.begin("bake.visibility");
    const GLuint vp = visibilityProg_.get();
    setLightMapUniforms(vp, lc);
    // The frame turns the normal towards u_lsEye: here towards the light, whichever side the
    // camera will see (the camera's lookup applies its own facing test).
    setVec3(vp, "u_lsEye",
            isDirectional(point) ? -1e4 * glm::normalize(point.wsDirection) : lc.lsPosition);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(sampleV_.fbo.get(), GL_COLOR, 0, zero);
    glBindFramebuffer(GL_FRAMEBUFFER, sampleV_.fbo.get());
    glBindTextureUnit(0, map_.get());
    drawAtlas(vp);
    timer_.end();
    timer_.begin("bake.weights");
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    const glm::dvec3 lsSample = frame.lsFromWs(wsSample);
    glProgramUniform3f(weightProg_.get(), glGetUniformLocation(weightProg_.get(), "u_lsSample"),
                       float(lsSample.x), float(lsSample.y), float(lsSample.z));
    glBindTextureUnit(1, texels_.textures[0].get());
    glBindTextureUnit(2, texels_.textures[1].get());
    fullScreen(weightProg_.get(), sums_.fbo.get(), sampleV_.textures[0].get());
    glDisable(GL_BLEND);
    timer_.end();
}

void Baker::fullScreen(GLuint program, GLuint fbo, GLuint source, GLuint geometry) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, atlas_.width, atlas_.height);
    glUseProgram(program);
    glBindTextureUnit(0, source);
    if (geometry) glBindTextureUnit(1, geometry);
    glBindVertexArray(geometry_.vao.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Filled texels of a (V, filled) target, counted by the samples the FILLED pass lets through.
uint64_t Baker::countFilled(GLuint source) {
    GlProgram filled =
        buildProgram("#define FILLED\n", shaders::fullscreen_vert, {shaders::lightmap_dilate_frag});
    setInt(filled.get(), "u_source", 0);
    const GlQuery q = makeQuery(GL_SAMPLES_PASSED);
    glBeginQuery(GL_SAMPLES_PASSED, q.get());
    // Into the spare target of the dilation's pair (its content is no longer needed).
    fullScreen(filled.get(), pong_.fbo.get(), source);
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 n = 0;
    glGetQueryObjectui64v(q.get(), GL_QUERY_RESULT, &n);
    return n;
}

// V from the sums, the dilation rings, the filled count, then V into the GL_R8 atlas.
void Baker::resolveAndDilate() {
    const int W = atlas_.width, H = atlas_.height;
    // The sample targets are no longer needed: free them before the dilation's pair.
    const GlTexture geometry = std::move(texels_.textures[0]);
    texels_ = {};
    sampleV_ = {};
    depth_ = {};
    map_ = {};
    mapFbos_.clear();
    ping_ = makeTarget({GL_RG32F}, W, H);
    pong_ = makeTarget({GL_RG32F}, W, H);
    auto program = [](const char* mode) {
        GlProgram p = buildProgram(std::string("#define ") + mode + "\n", shaders::fullscreen_vert,
                                   {shaders::lightmap_dilate_frag});
        setInt(p.get(), "u_source", 0);
        setInt(p.get(), "u_geometry", 1);
        return p;
    };
    timer_.begin("bake.dilate");
    const GlProgram resolve = program("RESOLVE"), dilate = program("DILATE");
    fullScreen(resolve.get(), ping_.fbo.get(), sums_.textures[0].get(), geometry.get());
    for (int i = 0; i < settings_.dilate; ++i) {
        fullScreen(dilate.get(), pong_.fbo.get(), ping_.textures[0].get());
        std::swap(ping_, pong_);
    }
    timer_.end();
    out_.texelsFilled = countFilled(ping_.textures[0].get());
    timer_.begin("bake.store");
    out_.atlas = makeTexture2D(GL_R8, W, H);
    GlFramebuffer store = makeFramebuffer();
    glNamedFramebufferTexture(store.get(), GL_COLOR_ATTACHMENT0, out_.atlas.get(), 0);
    const GlProgram storeProg = program("STORE");
    fullScreen(storeProg.get(), store.get(), ping_.textures[0].get());
    timer_.end();
}

BakedLightmap Baker::run() {
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);  // the light cameras' depth range
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(sums_.fbo.get(), GL_COLOR, 0, zero);
    texels();
    const std::vector<glm::dvec3> points = areaSampled_
                                               ? lightSamplePoints(light_, settings_.samples)
                                               : std::vector<glm::dvec3>{light_.wsPosition};
    for (const glm::dvec3& p : points) {
        sample(isAreaLight(light_) ? pointLightAt(light_, p) : light_, p);
    }
    out_.samples = int(points.size());
    resolveAndDilate();
    timer_.endFrame(true);
    for (const char* pass : {"bake.texels", "bake.shadow_map", "bake.visibility", "bake.weights",
                             "bake.dilate", "bake.store"})
        out_.passMs[pass] = timer_.stats(pass).median;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (GLuint unit = 0; unit < 3; ++unit) glBindTextureUnit(unit, 0);
    gpu_.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glFinish();
    return std::move(out_);
}

}  // namespace

BakedLightmap bakeLightmap(const Light& light, const GpuScene& scene, const LightmapAtlas& atlas,
                           const BakeSettings& settings) {
    return Baker(light, scene, atlas, settings).run();
}

}  // namespace so
