#include "raster_compare/rasterizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/camera.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/local_frame.h"
#include "raster_compare/gl_context.h"
#include "raster_compare/gl_object.h"
#include "raster_compare/light_camera.h"
#include "raster_compare/shaders.h"

namespace so {

namespace {

GlShader compileShader(GLenum stage, const std::string& source) {
    GlShader s(glCreateShader(stage));
    const char* text = source.c_str();
    glShaderSource(s.get(), 1, &text, nullptr);
    glCompileShader(s.get());
    GLint ok = 0;
    glGetShaderiv(s.get(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(s.get(), sizeof log, nullptr, log);
        throw std::runtime_error(std::string("shader compile failed: ") + log);
    }
    return s;
}

// "#version" first, then the variant's #defines, then the file.
GlProgram buildProgram(const std::string& defines, const char* vert, const char* frag) {
    const std::string header = "#version 450 core\n" + defines + "#line 1\n";
    GlShader vs = compileShader(GL_VERTEX_SHADER, header + vert);
    GlShader fs = compileShader(GL_FRAGMENT_SHADER, header + frag);
    GlProgram p(glCreateProgram());
    glAttachShader(p.get(), vs.get());
    glAttachShader(p.get(), fs.get());
    glLinkProgram(p.get());
    GLint ok = 0;
    glGetProgramiv(p.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetProgramInfoLog(p.get(), sizeof log, nullptr, log);
        throw std::runtime_error(std::string("program link failed: ") + log);
    }
    return p;
}

void setMat4(GLuint prog, const char* name, const glm::dmat4& m) {
    const glm::mat4 f(m);
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, name), 1, GL_FALSE,
                              glm::value_ptr(f));
}
void setVec3(GLuint prog, const char* name, const glm::dvec3& v) {
    glProgramUniform3f(prog, glGetUniformLocation(prog, name), float(v.x), float(v.y), float(v.z));
}
void setFloat(GLuint prog, const char* name, double v) {
    glProgramUniform1f(prog, glGetUniformLocation(prog, name), float(v));
}

GLenum depthFormat(int bits) {
    return bits == 16   ? GL_DEPTH_COMPONENT16
           : bits == 24 ? GL_DEPTH_COMPONENT24
                        : GL_DEPTH_COMPONENT32F;
}

struct MeshDraw {
    GLint first;
    GLsizei count;
};

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Times GL work with GL_TIME_ELAPSED queries; results are read after the frame.
class PassTimer {
  public:
    void begin(const std::string& pass) {
        queries_.push_back({pass, makeQuery(GL_TIME_ELAPSED)});
        glBeginQuery(GL_TIME_ELAPSED, queries_.back().query.get());
    }
    void end() { glEndQuery(GL_TIME_ELAPSED); }
    void collect(std::map<std::string, std::vector<double>>& msByPass) {
        for (auto& q : queries_) {
            GLuint64 ns = 0;
            glGetQueryObjectui64v(q.query.get(), GL_QUERY_RESULT, &ns);
            msByPass[q.pass].push_back(double(ns) * 1e-6);
        }
        queries_.clear();
    }

  private:
    struct Q {
        std::string pass;
        GlQuery query;
    };
    std::vector<Q> queries_;
};

}  // namespace

RasterResult renderRaster(const Scene& scene, const ShadowTechnique& technique,
                          const ParamValues& params, const RasterOptions& options,
                          const GlContext& gl) {
    CameraDesc camDesc = scene.camera;
    if (options.width > 0) camDesc.width = options.width;
    if (options.height > 0) camDesc.height = options.height;
    const Camera camera(camDesc);
    const int W = camera.width(), H = camera.height();
    const LocalFrame frame = LocalFrame::fit(scene.wsBounds);
    Bounds3d lsBounds;
    if (!scene.wsBounds.empty()) {
        lsBounds.extend(frame.lsFromWs(scene.wsBounds.lo));
        lsBounds.extend(frame.lsFromWs(scene.wsBounds.hi));
    }
    const int resolution = int(params.at("resolution"));
    const int depthBits = int(params.at("depth_format"));

    // Scene upload: triangles unshared, each vertex carrying its face normal (from double).
    std::vector<float> vertices;
    std::vector<MeshDraw> draws;
    for (const MeshPrimitive& m : scene.meshes) {
        draws.push_back({GLint(vertices.size() / 6), GLsizei(m.indices.size())});
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k)
                p[k] = frame.lsFromWs(m.wsPositions[m.indices[t + size_t(k)]]);
            glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
            const double len = glm::length(n);
            n = len > 0.0 ? n / len : glm::dvec3(0.0);  // degenerate: no fragments anyway
            for (int k = 0; k < 3; ++k)
                vertices.insert(vertices.end(), {float(p[k].x), float(p[k].y), float(p[k].z),
                                                 float(n.x), float(n.y), float(n.z)});
        }
    }
    GlBuffer vbo = makeBuffer();
    glNamedBufferStorage(vbo.get(),
                         GLsizeiptr(std::max<size_t>(1, vertices.size()) * sizeof(float)),
                         vertices.empty() ? nullptr : vertices.data(), 0);
    GlVertexArray vao = makeVertexArray();
    glVertexArrayVertexBuffer(vao.get(), 0, vbo.get(), 0, 6 * sizeof(float));
    for (GLuint a = 0; a < 2; ++a) {
        glEnableVertexArrayAttrib(vao.get(), a);
        glVertexArrayAttribFormat(vao.get(), a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao.get(), a, 0);
    }
    glBindVertexArray(vao.get());
    auto drawScene = [&](GLuint prog, bool setMeshId) {
        for (size_t i = 0; i < draws.size(); ++i) {
            if (setMeshId) setFloat(prog, "u_meshId", double(i));
            glDrawArrays(GL_TRIANGLES, draws[i].first, draws[i].count);
        }
    };

    // The camera: the same matrices as generateRay (tested in camera_test), with reversed float
    // depth and an infinite far plane for uniform precision.
    const glm::dmat4 wsFromLs = glm::scale(glm::translate(glm::dmat4(1.0), frame.wsCenter),
                                           glm::dvec3(std::ldexp(1.0, frame.exponent)));
    const glm::dvec3 lsEye = frame.lsFromWs(camera.wsEye());
    double lsNear =
        std::max(0.99 * glm::length(glm::clamp(lsEye, lsBounds.lo, lsBounds.hi) - lsEye), 1e-5);
    glm::dmat4 clipFromView = camera.clipFromView(1.0, 2.0);
    clipFromView[2][2] = 0.0;
    clipFromView[3][2] = frame.wsLength(lsNear);
    clipFromView[2][3] = -1.0;
    const glm::dmat4 cameraClipFromLocal = clipFromView * camera.viewFromWorld() * wsFromLs;

    // Programs.
    GlProgram geometryProg = buildProgram("", shaders::scene_vert, shaders::geometry_frag);
    GlProgram depthProg = buildProgram("", shaders::scene_vert, shaders::depth_frag);
    setMat4(geometryProg.get(), "u_clipFromLocal", cameraClipFromLocal);
    setVec3(geometryProg.get(), "u_lsEye", lsEye);

    // Camera targets.
    auto makeTarget = [&](GLenum format) {
        GlTexture t = makeTexture(GL_TEXTURE_2D);
        glTextureStorage2D(t.get(), 1, format, W, H);
        return t;
    };
    GlTexture positionTex = makeTarget(GL_RGBA32F), normalTex = makeTarget(GL_RGBA32F),
              primTex = makeTarget(GL_R32F);
    GlTexture cameraDepth = makeTarget(GL_DEPTH_COMPONENT32F);
    GlFramebuffer geometryFbo = makeFramebuffer();
    glNamedFramebufferTexture(geometryFbo.get(), GL_COLOR_ATTACHMENT0, positionTex.get(), 0);
    glNamedFramebufferTexture(geometryFbo.get(), GL_COLOR_ATTACHMENT1, normalTex.get(), 0);
    glNamedFramebufferTexture(geometryFbo.get(), GL_COLOR_ATTACHMENT2, primTex.get(), 0);
    glNamedFramebufferTexture(geometryFbo.get(), GL_DEPTH_ATTACHMENT, cameraDepth.get(), 0);
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(geometryFbo.get(), 3, buffers);

    // fit = 1: one camera pass first, to know which receivers are in view (local-frame bounds).
    Bounds3d lsReceivers;
    const bool fitToReceivers = params.count("fit") && params.at("fit") == 1.0;
    if (fitToReceivers) {
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(GL_GREATER);
        glViewport(0, 0, W, H);
        glBindFramebuffer(GL_FRAMEBUFFER, geometryFbo.get());
        const float zero4[4] = {0, 0, 0, 0}, zero = 0.0f;
        glClearNamedFramebufferfv(geometryFbo.get(), GL_COLOR, 0, zero4);
        glClearNamedFramebufferfv(geometryFbo.get(), GL_DEPTH, 0, &zero);
        glUseProgram(geometryProg.get());
        drawScene(geometryProg.get(), true);
        std::vector<float> pos(size_t(W) * size_t(H) * 4);
        glGetTextureImage(positionTex.get(), 0, GL_RGBA, GL_FLOAT,
                          GLsizei(pos.size() * sizeof(float)), pos.data());
        for (size_t i = 0; i < size_t(W) * size_t(H); ++i)
            if (pos[4 * i + 3] != 0.0f)
                lsReceivers.extend(glm::dvec3(pos[4 * i], pos[4 * i + 1], pos[4 * i + 2]));
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    // Per light: camera, shadow map, visibility program and target.
    struct LightPass {
        const Light* light = nullptr;
        LightCamera cam;
        GlTexture map;
        std::vector<GlFramebuffer> mapFbos;
        GlProgram visProg;
        GlTexture visTex, aliasTex;
        GlFramebuffer visFbo;
        // Filtered techniques: moments rendered per face, blurred twice into `map`.
        GlProgram momentsProg;
        GlTexture faceTex, tempTex, faceDepth;
        GlFramebuffer faceFbo, tempFbo;
    };
    const bool filtered = technique.filtered();
    const int blur = technique.blurRadius(params);
    const std::array<float, 4> farMoments = technique.farMoments(params);
    GlProgram blurProg = buildProgram("", shaders::fullscreen_vert, shaders::blur_frag);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    std::vector<LightPass> passes;
    for (const Light& light : scene.lights) {
        LightPass lp;
        lp.light = &light;
        lp.cam = fitLightCamera(light, frame, lsBounds, resolution,
                                fitToReceivers ? &lsReceivers : nullptr);
        const bool cube = lp.cam.kind == LightCamera::Kind::Cube;
        lp.map = makeTexture(cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D);
        glTextureStorage2D(lp.map.get(), 1, filtered ? GL_RGBA32F : depthFormat(depthBits),
                           resolution, resolution);
        // Point sampling: the techniques do their own filtering and comparison in the shader;
        // moment maps are filtered bilinearly, which is what they are for.
        const GLint filter = filtered ? GL_LINEAR : GL_NEAREST;
        glTextureParameteri(lp.map.get(), GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(lp.map.get(), GL_TEXTURE_MAG_FILTER, filter);
        glTextureParameteri(lp.map.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(lp.map.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(lp.map.get(), GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
        if (technique.hardwareCompare()) {
            glTextureParameteri(lp.map.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            glTextureParameteri(lp.map.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
            glTextureParameteri(lp.map.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(lp.map.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        }
        const GLenum attachment = filtered ? GL_COLOR_ATTACHMENT0 : GL_DEPTH_ATTACHMENT;
        for (int f = 0; f < lp.cam.faces; ++f) {
            GlFramebuffer fbo = makeFramebuffer();
            if (cube)
                glNamedFramebufferTextureLayer(fbo.get(), attachment, lp.map.get(), 0, f);
            else
                glNamedFramebufferTexture(fbo.get(), attachment, lp.map.get(), 0);
            glNamedFramebufferDrawBuffer(fbo.get(), filtered ? GL_COLOR_ATTACHMENT0 : GL_NONE);
            lp.mapFbos.push_back(std::move(fbo));
        }
        if (filtered) {
            auto square = [&](GLenum format, bool linear) {
                GlTexture t = makeTexture(GL_TEXTURE_2D);
                glTextureStorage2D(t.get(), 1, format, resolution, resolution);
                glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER,
                                    linear ? GL_LINEAR : GL_NEAREST);
                glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER,
                                    linear ? GL_LINEAR : GL_NEAREST);
                glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
                glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
                return t;
            };
            lp.faceTex = square(GL_RGBA32F, false);
            lp.tempTex = square(GL_RGBA32F, false);
            lp.faceDepth = square(depthFormat(depthBits), false);
            lp.faceFbo = makeFramebuffer();
            glNamedFramebufferTexture(lp.faceFbo.get(), GL_COLOR_ATTACHMENT0, lp.faceTex.get(), 0);
            glNamedFramebufferTexture(lp.faceFbo.get(), GL_DEPTH_ATTACHMENT, lp.faceDepth.get(), 0);
            lp.tempFbo = makeFramebuffer();
            glNamedFramebufferTexture(lp.tempFbo.get(), GL_COLOR_ATTACHMENT0, lp.tempTex.get(), 0);
            lp.momentsProg = buildProgram(technique.shaderDefines(params), shaders::scene_vert,
                                          shaders::moments_frag);
            setFloat(lp.momentsProg.get(), "u_near", lp.cam.near);
            setFloat(lp.momentsProg.get(), "u_far", lp.cam.far);
        }
        std::string defines = cube                                      ? "#define LIGHT_CUBE\n"
                              : lp.cam.kind == LightCamera::Kind::Ortho ? "#define LIGHT_ORTHO\n"
                                                                        : "#define LIGHT_SPOT\n";
        defines += technique.shaderDefines(params);
        lp.visProg = buildProgram(defines, shaders::scene_vert, shaders::visibility_frag);
        const GLuint vp = lp.visProg.get();
        setMat4(vp, "u_clipFromLocal", cameraClipFromLocal);
        setVec3(vp, "u_lsEye", lsEye);
        setVec3(vp, "u_lsLightPosition", lp.cam.lsPosition);
        setVec3(vp, "u_lsLightDirection", lp.cam.lsDirection);
        setFloat(vp, "u_cosOuter", lp.cam.cosOuter);
        setMat4(vp, "u_lightClipFromLocal", lp.cam.clipFromLocal(0));
        setMat4(vp, "u_lightViewFromLocal", lp.cam.viewFromLocal[0]);
        setFloat(vp, "u_near", lp.cam.near);
        setFloat(vp, "u_far", lp.cam.far);
        setFloat(vp, "u_texelScale", lp.cam.texelScale);
        glProgramUniform1i(vp, glGetUniformLocation(vp, "u_map"), 0);
        lp.visTex = makeTarget(GL_R32F);
        lp.visFbo = makeFramebuffer();
        glNamedFramebufferTexture(lp.visFbo.get(), GL_COLOR_ATTACHMENT0, lp.visTex.get(), 0);
        lp.aliasTex = makeTarget(GL_R32F);
        glNamedFramebufferTexture(lp.visFbo.get(), GL_COLOR_ATTACHMENT1, lp.aliasTex.get(), 0);
        const GLenum visBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glNamedFramebufferDrawBuffers(lp.visFbo.get(), 2, visBuffers);
        glNamedFramebufferTexture(lp.visFbo.get(), GL_DEPTH_ATTACHMENT, cameraDepth.get(), 0);
        setFloat(
            vp, "u_pixelScale",
            2.0 * std::tan(0.5 * camDesc.vfovDeg * 3.14159265358979323846 / 180.0) / double(H));
        passes.push_back(std::move(lp));
    }

    // Frames: shadow maps, camera pass, visibility passes; all timed.
    std::map<std::string, std::vector<double>> msByPass;
    std::vector<double> wallMs;
    for (int frameIndex = 0; frameIndex < options.warmup + options.frames; ++frameIndex) {
        PassTimer timer;
        const auto t0 = std::chrono::steady_clock::now();
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        for (LightPass& lp : passes) {
            timer.begin(lp.light->name + ".shadow_map");
            glViewport(0, 0, resolution, resolution);
            glUseProgram(depthProg.get());
            glDepthFunc(GL_LESS);
            technique.beginShadowPass(params);
            for (int f = 0; f < lp.cam.faces; ++f) {
                const float one = 1.0f;
                if (!filtered) {
                    glBindFramebuffer(GL_FRAMEBUFFER, lp.mapFbos[size_t(f)].get());
                    glClearNamedFramebufferfv(lp.mapFbos[size_t(f)].get(), GL_DEPTH, 0, &one);
                    setMat4(depthProg.get(), "u_clipFromLocal", lp.cam.clipFromLocal(f));
                    drawScene(depthProg.get(), false);
                    continue;
                }
                // Moments of this face, then the two blur directions into the map's face.
                glBindFramebuffer(GL_FRAMEBUFFER, lp.faceFbo.get());
                glClearNamedFramebufferfv(lp.faceFbo.get(), GL_COLOR, 0, farMoments.data());
                glClearNamedFramebufferfv(lp.faceFbo.get(), GL_DEPTH, 0, &one);
                glUseProgram(lp.momentsProg.get());
                setMat4(lp.momentsProg.get(), "u_clipFromLocal", lp.cam.clipFromLocal(f));
                setMat4(lp.momentsProg.get(), "u_lightViewFromLocal",
                        lp.cam.viewFromLocal[size_t(f)]);
                drawScene(lp.momentsProg.get(), false);
                glDisable(GL_DEPTH_TEST);
                glUseProgram(blurProg.get());
                glProgramUniform1i(blurProg.get(), glGetUniformLocation(blurProg.get(), "u_radius"),
                                   blur);
                glProgramUniform1i(blurProg.get(), glGetUniformLocation(blurProg.get(), "u_source"),
                                   0);
                const float texel = 1.0f / float(resolution);
                glBindFramebuffer(GL_FRAMEBUFFER, lp.tempFbo.get());
                glBindTextureUnit(0, lp.faceTex.get());
                glProgramUniform2f(blurProg.get(), glGetUniformLocation(blurProg.get(), "u_step"),
                                   texel, 0.0f);
                glDrawArrays(GL_TRIANGLES, 0, 3);
                glBindFramebuffer(GL_FRAMEBUFFER, lp.mapFbos[size_t(f)].get());
                glBindTextureUnit(0, lp.tempTex.get());
                glProgramUniform2f(blurProg.get(), glGetUniformLocation(blurProg.get(), "u_step"),
                                   0.0f, texel);
                glDrawArrays(GL_TRIANGLES, 0, 3);
                glEnable(GL_DEPTH_TEST);
            }
            technique.endShadowPass(params);
            timer.end();
        }
        timer.begin("camera");
        glViewport(0, 0, W, H);
        glBindFramebuffer(GL_FRAMEBUFFER, geometryFbo.get());
        const float zero4[4] = {0, 0, 0, 0}, normalClear[4] = {0, 0, 0, -1},
                    primClear[4] = {-1, 0, 0, 0}, zero = 0.0f;
        glClearNamedFramebufferfv(geometryFbo.get(), GL_COLOR, 0, zero4);
        glClearNamedFramebufferfv(geometryFbo.get(), GL_COLOR, 1, normalClear);
        glClearNamedFramebufferfv(geometryFbo.get(), GL_COLOR, 2, primClear);
        glClearNamedFramebufferfv(geometryFbo.get(), GL_DEPTH, 0,
                                  &zero);  // reversed depth: 0 is far
        glDepthFunc(GL_GREATER);
        glUseProgram(geometryProg.get());
        drawScene(geometryProg.get(), true);
        timer.end();
        glDepthMask(GL_FALSE);
        glDepthFunc(GL_EQUAL);
        for (LightPass& lp : passes) {
            timer.begin(lp.light->name + ".visibility");
            glBindFramebuffer(GL_FRAMEBUFFER, lp.visFbo.get());
            glClearNamedFramebufferfv(lp.visFbo.get(), GL_COLOR, 0, zero4);
            glClearNamedFramebufferfv(lp.visFbo.get(), GL_COLOR, 1, zero4);
            glUseProgram(lp.visProg.get());
            glBindTextureUnit(0, lp.map.get());
            drawScene(lp.visProg.get(), false);
            timer.end();
        }
        glFinish();
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        std::map<std::string, std::vector<double>> frameMs;
        timer.collect(frameMs);
        if (frameIndex >= options.warmup) {
            wallMs.push_back(ms);
            for (auto& [k, v] : frameMs) msByPass[k].insert(msByPass[k].end(), v.begin(), v.end());
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    // Readback, rows flipped: GL's row 0 is the bottom, ours the top.
    auto read = [&](GLuint tex, GLenum format, int comps) {
        std::vector<float> data(size_t(W) * size_t(H) * size_t(comps));
        glGetTextureImage(tex, 0, format, GL_FLOAT, GLsizei(data.size() * sizeof(float)),
                          data.data());
        return data;
    };
    const std::vector<float> pos = read(positionTex.get(), GL_RGBA, 4),
                             nrm = read(normalTex.get(), GL_RGBA, 4),
                             prim = read(primTex.get(), GL_RED, 1);
    RasterResult result;
    ChannelImage& img = result.image;
    img = ChannelImage(W, H);
    namespace ch = channels;
    float* A = img.addChannel(ch::kHit);
    float* P[3] = {img.addChannel(ch::kPX), img.addChannel(ch::kPY), img.addChannel(ch::kPZ)};
    float* N[3] = {img.addChannel(ch::kNX), img.addChannel(ch::kNY), img.addChannel(ch::kNZ)};
    float* Z = img.addChannel(ch::kDepth, std::numeric_limits<float>::infinity());
    float* meshId = img.addChannel(ch::kMeshId, -1.0f);
    float* primId = img.addChannel(ch::kPrimId, -1.0f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t src = size_t(H - 1 - y) * size_t(W) + size_t(x),
                         dst = size_t(y) * size_t(W) + size_t(x);
            if (pos[4 * src + 3] == 0.0f) continue;
            A[dst] = 1.0f;
            const glm::dvec3 ws =
                frame.wsFromLs(glm::dvec3(pos[4 * src], pos[4 * src + 1], pos[4 * src + 2]));
            for (int k = 0; k < 3; ++k) {
                P[k][dst] = float(ws[k]);
                N[k][dst] = nrm[4 * src + size_t(k)];
            }
            Z[dst] = float(glm::length(ws - camera.wsEye()));
            meshId[dst] = nrm[4 * src + 3];
            primId[dst] = prim[src];
        }
    nlohmann::json lights = nlohmann::json::array();
    for (LightPass& lp : passes) {
        const std::vector<float> vis = read(lp.visTex.get(), GL_RED, 1);
        float* V = img.addChannel(ch::lightChannel(lp.light->name, ch::kVisibility));
        const std::vector<float> alias = read(lp.aliasTex.get(), GL_RED, 1);
        float* AP = img.addChannel(ch::lightChannel(lp.light->name, ch::kPredictedAliasing));
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t src = size_t(H - 1 - y) * size_t(W) + size_t(x),
                             dst = size_t(y) * size_t(W) + size_t(x);
                V[dst] = vis[src];
                AP[dst] = alias[src];
            }
        nlohmann::json faces = nlohmann::json::array();
        const glm::dmat4 lsFromWs = glm::inverse(wsFromLs);
        for (int f = 0; f < lp.cam.faces; ++f) {
            const glm::dmat4 m = lp.cam.clipFromLocal(f) * lsFromWs;  // clip from world
            nlohmann::json rows = nlohmann::json::array();
            for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
            faces.push_back(rows);
        }
        const char* kind = lp.cam.kind == LightCamera::Kind::Ortho  ? "orthographic"
                           : lp.cam.kind == LightCamera::Kind::Cube ? "cube"
                                                                    : "perspective";
        lights.push_back(
            {{"name", lp.light->name},
             {"type", lightTypeName(lp.light->type)},
             {"map", kind},
             {"clip_from_world", faces},
             {"near", frame.wsLength(lp.cam.near)},
             {"far", frame.wsLength(lp.cam.far)},
             {"fov_y_deg", lp.cam.fovYDeg},
             {lp.cam.kind == LightCamera::Kind::Ortho ? "texel_size" : "texel_size_per_unit_depth",
              lp.cam.kind == LightCamera::Kind::Ortho ? frame.wsLength(lp.cam.texelScale)
                                                      : lp.cam.texelScale},
             {"shadow_map_ms", median(msByPass[lp.light->name + ".shadow_map"])},
             {"visibility_ms", median(msByPass[lp.light->name + ".visibility"])}});
    }
    nlohmann::json paramJson = nlohmann::json::object();
    for (const auto& [k, v] : params) paramJson[k] = v;
    result.stats = {
        {"technique", technique.name()},
        {"parameters", paramJson},
        {"image", {{"width", W}, {"height", H}}},
        {"gl",
         {{"renderer", gl.renderer()}, {"version", gl.version()}, {"platform", gl.platform()}}},
        {"lights", lights},
        {"timings",
         {{"frames", options.frames},
          {"warmup_frames", options.warmup},
          {"camera_ms", median(msByPass["camera"])},
          {"wall_ms", median(wallMs)},
          {"note",
           "median over the timed frames; GL_TIME_ELAPSED queries (on llvmpipe they measure CPU "
           "work)"}}}};
    return result;
}

}  // namespace so
