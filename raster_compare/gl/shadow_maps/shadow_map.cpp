#include "raster_compare/gl/shadow_maps/shadow_map.h"

#include <algorithm>

#include <glm/matrix.hpp>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {

ParamSpec fitParam() {
    return methodParam("fit", 0, {"bounds", "receivers"},
                       "directional maps: fitted to the scene's bounds, or only to the receivers "
                       "in view");
}

ParamTable shadowMapParams(ParamTable own) {
    ParamTable p = {
        {"resolution", 2048, 16, 16384, true,
         "shadow map side in texels (cube maps: per face; cascades: each)"},
        {"depth_format",
         24,
         16,
         32,
         true,
         "depth buffer bits: 16, 24 (fixed point) or 32 (float)",
         {16, 24, 32}},
        fitParam(),
        {"cascades", 1, 1, 8, true,
         "directional lights: maps over slices of the view's depth range (1: one map); others "
         "ignore it"},
        {"split_lambda", 0.5, 0.0, 1.0, false,
         "cascades' practical split: 0 uniform, 1 logarithmic"},
        methodParam("snap", 1, {"off", "on"},
                    "cascades: on, a bounding-sphere fit with texel snapping; off, each slice's "
                    "tight box"),
        {"blend", 0.1, 0.0, 0.5, false,
         "cascades: fraction of each one's depth range over which it fades into the next"},
    };
    for (ParamSpec& s : ContactShadows::params()) p.push_back(std::move(s));
    // The resolution is the family's quality parameter unless the technique names its own.
    p[0].quality = qualityParam(own) == nullptr;
    for (ParamSpec& s : own) p.push_back(std::move(s));
    return p;
}

ParamTable withBiasAxis(ParamTable own, const std::string& defaultBias) {
    for (ParamSpec& s : biasAxisParams(defaultBias)) own.push_back(std::move(s));
    return own;
}

ShadowMapTechnique::ShadowMapTechnique(const ParamValues& v)
    : Technique(v),
      resolution_(v.integer("resolution")),
      depthBits_(v.integer("depth_format")),
      fitToReceivers_(v.integer("fit") == 1),
      cascades_{v.integer("cascades"), v.real("split_lambda"), v.integer("snap") == 1},
      blend_(v.real("blend")),
      contact_(v),
      bias_(v.all().count("bias") ? createDepthBias(v) : nullptr) {}

ParamTable SlopeBias::params() {
    // Was `alpha`, the name left to alpha masks (issue 62).
    return {
        renamedFrom({"slope_factor", 1.0, 0.0, 100.0, false, "slope factor"}, {"alpha", {}, "", 8}),
        {"min", 0.1, 0.0, 1000.0, false, "smallest bias in texels"},
        {"max", 10.0, 0.0, 1000.0, false, "largest bias in texels"}};
}

SlopeBias::SlopeBias(const ParamValues& v)
    : factor(v.real("slope_factor")), minTexels(v.real("min")), maxTexels(v.real("max")) {}

std::string SlopeBias::defines() const {
    return glslDefine("SLOPE_FACTOR", factor) + glslDefine("SLOPE_MIN", minTexels) +
           glslDefine("SLOPE_MAX", maxTexels);
}

ParamTable DepthPrecision::params() {
    return {{"epsilon", 2.0, 0.0, 1e6, false,
             "margin for the depth buffer's rounding, in steps of its last bit at the receiver's "
             "depth (a 32-bit float's mantissa counts 24 bits)"}};
}

DepthPrecision::DepthPrecision(const ParamValues& v) : steps(v.real("epsilon")) {}

std::string DepthPrecision::defines(int depthBits) const {
    return "#define RECEIVER_PLANE\n#define DEPTH_BITS " + std::to_string(std::min(depthBits, 24)) +
           "\n" + glslDefine("DEPTH_STEPS", steps);
}

void setLightCameraUniforms(GLuint program, const CameraPass& camera, const LightCamera& lc) {
    setMat4(program, "u_clipFromLocal", camera.clipFromLocal());
    setVec3(program, "u_lsEye", camera.lsEye());
    setFloat(program, "u_pixelScale", camera.pixelScale());
    setLightMapUniforms(program, lc);
}

void setLightMapUniforms(GLuint program, const LightCamera& lc) {
    setVec3(program, "u_lsLightPosition", lc.lsPosition);
    setVec3(program, "u_lsLightDirection", lc.lsDirection);
    setFloat(program, "u_cosOuter", lc.cosOuter);
    setVec3(program, "u_lsEmitNormal", lc.lsEmitNormal);
    setMat4(program, "u_lightClipFromLocal", lc.clipFromLocal(0));
    setMat4(program, "u_lightViewFromLocal", lc.viewFromLocal[0]);
    setFloat(program, "u_near", lc.near);
    setFloat(program, "u_far", lc.far);
    setFloat(program, "u_texelScale", lc.texelScale);
}

namespace {

GLenum depthFormat(int bits) {
    return bits == 16   ? GL_DEPTH_COMPONENT16
           : bits == 24 ? GL_DEPTH_COMPONENT24
                        : GL_DEPTH_COMPONENT32F;
}

// The camera's frame and the depth range of what it sees (the renderer rendered it for the
// receivers' bounds, needsReceiverBounds).
CascadeView cascadeView(const CameraPass& camera) {
    const Camera& c = camera.camera();
    CascadeView v;
    v.lsEye = camera.lsEye();
    v.forward = c.wsForward(), v.right = c.wsRight(), v.up = c.wsUp();
    v.tanHalfVfov = 0.5 * camera.pixelScale() * double(camera.height());
    v.aspect = double(camera.width()) / double(camera.height());
    // The range the renderer's receiverBounds() readback found (no second readback).
    const double nearest = camera.visibleDepthRange().nearest,
                 farthest = camera.visibleDepthRange().farthest;
    // Nothing in view: any range will do.
    v.lsNearest = farthest > 0.0 ? std::max(nearest, 0.0) : 1e-3;
    v.lsFarthest = farthest > 0.0 ? farthest : 1.0;
    return v;
}

// One light's map and passes.
class ShadowMapLight final : public LightTechnique {
  public:
    ShadowMapLight(const ShadowMapTechnique& technique, const LightSetup& setup);
    std::vector<std::string> passNames() const override { return {"shadow_map", "visibility"}; }
    void renderLightPasses(PassClock& clock) override;
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override;
    bool probeDepth(bool on) override {
        probing_ = on && probeProg_.get() != 0;
        return probeProg_.get() != 0;
    }
    // With contact shadows, the map's own V (the probe's fourth value) is the V before a
    // screen-space pass, as blur's is: their false shadows are screen-space bleed, not acne.
    std::optional<DepthComparison> readDepthComparison(const LightTarget& own) const override {
        if (probeProg_.get() == 0 || !own.hasDepthProbe()) return std::nullopt;
        DepthComparison c{own.readDepthProbe(), {}};
        if (technique_.contact().on)
            for (size_t i = 3; i < c.probe.size(); i += 4)
                c.unfilteredVisibility.push_back(c.probe[i]);
        return c;
    }

  private:
    void createMap();
    void createMomentTargets();
    void createCubeBlur();
    void blurCubeAcrossFaces();
    GlProgram createVisibilityProgram(const CameraPass& camera, bool probe) const;
    void setCascadeUniforms(GLuint program, const CameraPass& camera) const;
    void renderMomentFace(int face);

    const ShadowMapTechnique& technique_;
    const Light& light_;
    const GpuScene& scene_;
    const CameraPass& camera_;  // contact shadows read its images
    LightCamera cam_;
    GlTexture map_;
    std::vector<GlFramebuffer> mapFbos_;  // one per face
    GlProgram depthProg_, visibilityProg_;
    // Moment maps: each face rendered into faceTex_, blurred across into tempTex_, then down into
    // the map's face.
    GlProgram momentsProg_, blurProg_;
    GlTexture faceTex_, tempTex_, faceDepth_;
    GlFramebuffer faceFbo_, tempFbo_;
    // Without a blur (radius 0) the moments go straight into the map's faces, over faceDepth_:
    // the same values as the blur's one-tap copy, without the two copies. A cube map's go there
    // too, to be blurred across its faces (cube_blur.frag): every face padded by `radius` texels
    // of what the cube holds beyond it (padded), then each blurred along s into acrossTarget and
    // along t back into the map's face.
    std::vector<GlFramebuffer> directFbos_;
    struct CubeBlur {
        GlProgram padInside, padBorder, across, down;
        GlTexture faces;  // the map's faces as the layers of a 2D array (a view)
        GlTexture padded, acrossTarget;
        std::vector<GlFramebuffer> paddedFbos;
        GlFramebuffer acrossFbo;
    };
    std::unique_ptr<CubeBlur> cubeBlur_;
    int receiver_ = -1;  // technique_.receiverMesh
    // The visibility program that also writes the depth probe (LightSetup::depthProbe; none
    // otherwise), run instead of visibilityProg_ while probing.
    GlProgram probeProg_;
    bool probing_ = false;
    int frameIndex_ = 0;  // LightSetup::frameIndex: u_frameIndex of the visibility programs
};

ShadowMapLight::ShadowMapLight(const ShadowMapTechnique& technique, const LightSetup& setup)
    : technique_(technique),
      light_(setup.light),
      scene_(setup.scene),
      camera_(setup.camera),
      frameIndex_(setup.frameIndex) {
    if (isDirectional(light_) && technique.cascades().count > 1)
        cam_ = fitCascades(light_, scene_.lsBounds(), technique.resolution(),
                           cascadeView(setup.camera), technique.cascades());
    else
        cam_ = fitLightCamera(light_, scene_.frame(), scene_.lsBounds(), technique.resolution(),
                              setup.lsReceivers ? &*setup.lsReceivers : nullptr);
    receiver_ = technique.receiverMesh(scene_);
    depthProg_ = buildProgram(scene_.alphaDefines(), shaders::scene_vert,
                              {shaders::alpha_test_glsl, shaders::depth_frag});
    createMap();
    if (technique.storage() == MapStorage::Moments) createMomentTargets();
    visibilityProg_ = createVisibilityProgram(setup.camera, false);
    if (setup.depthProbe && technique.probesDepth())
        probeProg_ = createVisibilityProgram(setup.camera, true);
}

void ShadowMapLight::createMap() {
    const MapStorage storage = technique_.storage();
    const bool cube = cam_.kind == LightCamera::Kind::Cube,
               cascades = cam_.kind == LightCamera::Kind::Cascades,
               moments = storage == MapStorage::Moments;
    const int res = technique_.resolution();
    const GLenum format = moments ? GL_RGBA32F : depthFormat(technique_.depthBits());
    map_ = makeTexture(cube ? GL_TEXTURE_CUBE_MAP : cascades ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D);
    if (cascades)
        glTextureStorage3D(map_.get(), 1, format, res, res, cam_.faces);
    else
        glTextureStorage2D(map_.get(), 1, format, res, res);
    // Point sampling: depth techniques do their own filtering and comparison in the shader;
    // moment maps are filtered bilinearly, which is what they are for; the hardware compare
    // filters with GL_LINEAR.
    const GLint filter = storage == MapStorage::Depth || (moments && !technique_.bilinearMap())
                             ? GL_NEAREST
                             : GL_LINEAR;
    glTextureParameteri(map_.get(), GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(map_.get(), GL_TEXTURE_MAG_FILTER, filter);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(map_.get(), wrap, GL_CLAMP_TO_EDGE);
    if (storage == MapStorage::DepthHardwareCompare) {
        glTextureParameteri(map_.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(map_.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    const GLenum attachment = moments ? GL_COLOR_ATTACHMENT0 : GL_DEPTH_ATTACHMENT;
    for (int f = 0; f < cam_.faces; ++f) {
        GlFramebuffer fbo = makeFramebuffer();
        if (cube || cascades)
            glNamedFramebufferTextureLayer(fbo.get(), attachment, map_.get(), 0, f);
        else
            glNamedFramebufferTexture(fbo.get(), attachment, map_.get(), 0);
        glNamedFramebufferDrawBuffer(fbo.get(), moments ? GL_COLOR_ATTACHMENT0 : GL_NONE);
        mapFbos_.push_back(std::move(fbo));
    }
}

void ShadowMapLight::createMomentTargets() {
    const int res = technique_.resolution();
    faceDepth_ = makeTexture2D(depthFormat(technique_.depthBits()), res, res);
    momentsProg_ = buildProgram(
        scene_.alphaDefines() + ("#define MOMENTS_PASS\n" + technique_.shaderDefines()),
        shaders::scene_vert,
        {shaders::alpha_test_glsl, shaders::shadow_moments_frag, technique_.glsl()});
    setFloat(momentsProg_.get(), "u_near", cam_.near);
    setFloat(momentsProg_.get(), "u_far", cam_.far);
    const bool cube = cam_.kind == LightCamera::Kind::Cube;
    if (technique_.blurRadius() == 0 || cube) {
        for (int f = 0; f < cam_.faces; ++f) {
            GlFramebuffer fbo = makeFramebuffer();
            if (cam_.kind != LightCamera::Kind::Ortho &&
                cam_.kind != LightCamera::Kind::Perspective)
                glNamedFramebufferTextureLayer(fbo.get(), GL_COLOR_ATTACHMENT0, map_.get(), 0, f);
            else
                glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, map_.get(), 0);
            glNamedFramebufferTexture(fbo.get(), GL_DEPTH_ATTACHMENT, faceDepth_.get(), 0);
            directFbos_.push_back(std::move(fbo));
        }
        if (cube && technique_.blurRadius() > 0) createCubeBlur();
        return;
    }
    faceTex_ = makeTexture2D(GL_RGBA32F, res, res);
    tempTex_ = makeTexture2D(GL_RGBA32F, res, res);
    faceFbo_ = makeFramebuffer();
    glNamedFramebufferTexture(faceFbo_.get(), GL_COLOR_ATTACHMENT0, faceTex_.get(), 0);
    glNamedFramebufferTexture(faceFbo_.get(), GL_DEPTH_ATTACHMENT, faceDepth_.get(), 0);
    tempFbo_ = makeFramebuffer();
    glNamedFramebufferTexture(tempFbo_.get(), GL_COLOR_ATTACHMENT0, tempTex_.get(), 0);
    blurProg_ = buildProgram(
        "#define SOURCE_TEXEL_BYTES " + std::to_string(texelBytes(faceTex_.get())) + "\n",
        shaders::fullscreen_vert, {shaders::blur_frag});
    setInt(blurProg_.get(), "u_radius", technique_.blurRadius());
    setInt(blurProg_.get(), "u_source", 0);
}

void ShadowMapLight::createCubeBlur() {
    const int res = technique_.resolution(), radius = technique_.blurRadius(),
              padded = res + 2 * radius;
    cubeBlur_ = std::make_unique<CubeBlur>();
    CubeBlur& b = *cubeBlur_;
    // A view's name must come from glGenTextures, unbound.
    GLuint view = 0;
    glGenTextures(1, &view);
    b.faces = GlTexture(view);
    glTextureView(view, GL_TEXTURE_2D_ARRAY, map_.get(), GL_RGBA32F, 0, 1, 0, 6);
    const auto makeLayers = [](int width, int height, int layers) {
        GlTexture t = makeTexture(GL_TEXTURE_2D_ARRAY);
        glTextureStorage3D(t.get(), 1, GL_RGBA32F, width, height, layers);
        for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER})
            glTextureParameteri(t.get(), p, GL_NEAREST);
        return t;
    };
    b.padded = makeLayers(padded, padded, 6);
    b.acrossTarget = makeLayers(res, padded, 1);
    for (int f = 0; f < 6; ++f) {
        GlFramebuffer fbo = makeFramebuffer();
        glNamedFramebufferTextureLayer(fbo.get(), GL_COLOR_ATTACHMENT0, b.padded.get(), 0, f);
        b.paddedFbos.push_back(std::move(fbo));
    }
    b.acrossFbo = makeFramebuffer();
    glNamedFramebufferTextureLayer(b.acrossFbo.get(), GL_COLOR_ATTACHMENT0, b.acrossTarget.get(), 0,
                                   0);
    const std::string bytes =
        "#define SOURCE_TEXEL_BYTES " + std::to_string(texelBytes(map_.get())) +
        "\n#define SOURCE_TAP_TEXELS " + (technique_.bilinearMap() ? "4" : "1") + "\n";
    const auto program = [&](const std::string& defines) {
        GlProgram p =
            buildProgram(defines + bytes, shaders::fullscreen_vert, {shaders::cube_blur_frag});
        setInt(p.get(), "u_radius", radius);
        setInt(p.get(), "u_size", res);
        setInt(p.get(), "u_source", 0);
        return p;
    };
    b.padInside = program("#define PAD\n#define INSIDE\n");
    b.padBorder = program("#define PAD\n");
    b.across = program("#define ACROSS\n");
    b.down = program("");
}

// Every face's moments are in the map: each face padded from the whole cube, then blurred along s
// and along t back into the map's face.
void ShadowMapLight::blurCubeAcrossFaces() {
    const CubeBlur& b = *cubeBlur_;
    const int res = technique_.resolution(), r = technique_.blurRadius(), padded = res + 2 * r;
    const auto draw = [](GLuint program, int face) {
        glUseProgram(program);
        glProgramUniform1i(program, glGetUniformLocation(program, "u_face"), face);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    glDisable(GL_DEPTH_TEST);
    // The border reads the cube unblurred: every face is padded before any is blurred. The middle
    // and the four strips of the border are drawn apart, so the cube is looked up only there.
    const std::array<std::array<int, 4>, 4> strips = {
        {{0, 0, padded, r}, {0, padded - r, padded, r}, {0, r, r, res}, {padded - r, r, r, res}}};
    for (int f = 0; f < 6; ++f) {
        glBindFramebuffer(GL_FRAMEBUFFER, b.paddedFbos[size_t(f)].get());
        glViewport(r, r, res, res);
        glBindTextureUnit(0, b.faces.get());
        draw(b.padInside.get(), f);
        glBindTextureUnit(0, map_.get());
        for (const auto& [x, y, w, h] : strips) {
            glViewport(x, y, w, h);
            draw(b.padBorder.get(), f);
        }
    }
    for (int f = 0; f < 6; ++f) {
        glBindFramebuffer(GL_FRAMEBUFFER, b.acrossFbo.get());
        glViewport(0, 0, res, padded);
        glBindTextureUnit(0, b.padded.get());
        draw(b.across.get(), f);
        glBindFramebuffer(GL_FRAMEBUFFER, mapFbos_[size_t(f)].get());
        glViewport(0, 0, res, res);
        glBindTextureUnit(0, b.acrossTarget.get());
        draw(b.down.get(), 0);
    }
    glEnable(GL_DEPTH_TEST);
}

std::string mapDefines(const ShadowMapTechnique& technique, GLuint map) {
    const MapStorage storage = technique.storage();
    const bool filtered = storage == MapStorage::DepthHardwareCompare ||
                          (storage == MapStorage::Moments && technique.bilinearMap());
    return std::string(storage == MapStorage::Depth                  ? "#define MAP_DEPTH\n"
                       : storage == MapStorage::DepthHardwareCompare ? "#define MAP_HW_COMPARE\n"
                                                                     : "#define MAP_MOMENTS\n") +
           "#define MAP_TEXEL_BYTES " + std::to_string(texelBytes(map)) +
           "\n#define MAP_FILTER_TEXELS " + (filtered ? "4" : "1") + "\n";
}

GlProgram ShadowMapLight::createVisibilityProgram(const CameraPass& camera, bool probe) const {
    const std::string defines =
        scene_.alphaDefines() +
        ("#define VISIBILITY_PASS\n" + lightCameraDefines(cam_) +
         mapDefines(technique_, map_.get()) + technique_.shaderDefines() +
         (technique_.depthBias() ? technique_.depthBias()->defines(technique_.depthBits()) : "") +
         (probe ? "#define DEPTH_PROBE\n" : "") + technique_.contact().defines(camera));
    std::vector<const char*> sources = {shaders::alpha_test_glsl, shaders::taps_glsl,
                                        shaders::shadow_map_frag};
    if (technique_.depthBias()) sources.push_back(technique_.depthBias()->glsl());
    sources.push_back(technique_.glsl());
    for (const char* s : technique_.contact().sources()) sources.push_back(s);
    GlProgram program = buildProgram(defines, shaders::scene_vert, sources);
    const GLuint vp = program.get();
    technique_.contact().setUniforms(vp, scene_.frame());
    setLightCameraUniforms(vp, camera, cam_);
    setInt(vp, "u_map", 0);
    setFloat(vp, "u_receiverMesh", receiver_);
    setInt(vp, "u_frameIndex", frameIndex_);  // read only by temporal=on's taps
    if (cam_.kind == LightCamera::Kind::Cascades) setCascadeUniforms(vp, camera);
    technique_.setLightUniforms(vp, light_, scene_.frame());
    return program;
}

void ShadowMapLight::setCascadeUniforms(GLuint vp, const CameraPass& camera) const {
    setVec3(vp, "u_lsCameraForward", camera.camera().wsForward());
    setFloat(vp, "u_cascadeBlend", technique_.cascadeBlend());
    for (int i = 0; i <= cam_.faces; ++i) {
        const std::string k = "[" + std::to_string(i) + "]";
        setFloat(vp, ("u_cascadeSplit" + k).c_str(), cam_.lsSplits[size_t(i)]);
        if (i == cam_.faces) break;
        setMat4(vp, ("u_cascadeClipFromLocal" + k).c_str(), cam_.clipFromLocal(i));
        setFloat(vp, ("u_cascadeTexel" + k).c_str(), cam_.cascadeTexel[size_t(i)]);
    }
}

void ShadowMapLight::renderLightPasses(PassClock& clock) {
    clock.begin("shadow_map");
    const int res = technique_.resolution();
    glViewport(0, 0, res, res);
    glUseProgram(depthProg_.get());
    glDepthFunc(GL_LESS);
    technique_.beginMapPass();
    if (technique_.depthBias()) technique_.depthBias()->beginMapPass();
    for (int f = 0; f < cam_.faces; ++f) {
        if (technique_.storage() == MapStorage::Moments) {
            renderMomentFace(f);
            continue;
        }
        const float one = 1.0f;
        glBindFramebuffer(GL_FRAMEBUFFER, mapFbos_[size_t(f)].get());
        glClearNamedFramebufferfv(mapFbos_[size_t(f)].get(), GL_DEPTH, 0, &one);
        setMat4(depthProg_.get(), "u_clipFromLocal", cam_.clipFromLocal(f));
        scene_.draw(depthProg_.get(), false);
    }
    if (cubeBlur_) blurCubeAcrossFaces();
    if (technique_.depthBias()) technique_.depthBias()->endMapPass();
    technique_.endMapPass();
    clock.end();
}

// The moments of one face, then the two blur directions into the map's face.
void ShadowMapLight::renderMomentFace(int f) {
    const float one = 1.0f;
    const std::array<float, 4> farMoments = technique_.farMoments();
    const bool direct = !directFbos_.empty();
    const GLuint target = direct ? directFbos_[size_t(f)].get() : faceFbo_.get();
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glClearNamedFramebufferfv(target, GL_COLOR, 0, farMoments.data());
    glClearNamedFramebufferfv(target, GL_DEPTH, 0, &one);
    glUseProgram(momentsProg_.get());
    setMat4(momentsProg_.get(), "u_clipFromLocal", cam_.clipFromLocal(f));
    setMat4(momentsProg_.get(), "u_lightViewFromLocal", cam_.viewFromLocal[size_t(f)]);
    for (size_t m = 0; m < scene_.meshCount(); ++m)
        if (int(m) != receiver_) scene_.drawMesh(momentsProg_.get(), m);
    if (direct) return;
    glDisable(GL_DEPTH_TEST);
    glUseProgram(blurProg_.get());
    const float texel = 1.0f / float(technique_.resolution());
    const GLint step = glGetUniformLocation(blurProg_.get(), "u_step");
    glBindFramebuffer(GL_FRAMEBUFFER, tempFbo_.get());
    glBindTextureUnit(0, faceTex_.get());
    glProgramUniform2f(blurProg_.get(), step, texel, 0.0f);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, mapFbos_[size_t(f)].get());
    glBindTextureUnit(0, tempTex_.get());
    glProgramUniform2f(blurProg_.get(), step, 0.0f, texel);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
}

void ShadowMapLight::renderVisibility(PassClock& clock) {
    clock.begin("visibility");
    const GLuint program = probing_ ? probeProg_.get() : visibilityProg_.get();
    glUseProgram(program);
    glBindTextureUnit(0, map_.get());
    technique_.contact().bindCameraImages(camera_);
    scene_.draw(program, receiver_ >= 0);
    clock.end();
}

RasterLightStats ShadowMapLight::describe() const {
    const LocalFrame& frame = scene_.frame();
    RasterLightStats s;
    if (receiver_ >= 0) s.counts = {{"receiver_mesh", receiver_}};
    const bool ortho = cam_.kind == LightCamera::Kind::Ortho;
    // Cascades: the first (finest) cascade's texel.
    const bool cascades = cam_.kind == LightCamera::Kind::Cascades;
    s.map = ortho                                  ? "orthographic"
            : cascades                             ? "cascades"
            : cam_.kind == LightCamera::Kind::Cube ? "cube"
                                                   : "perspective";
    if (cascades) s.counts["cascades"] = cam_.faces;
    const glm::dmat4 lsFromWs = glm::inverse(scene_.wsFromLs());
    for (int f = 0; f < cam_.faces; ++f)
        s.clipFromWorld.push_back(cam_.clipFromLocal(f) * lsFromWs);
    s.wsNear = frame.wsLength(cam_.near);
    s.wsFar = frame.wsLength(cam_.far);
    s.fovYDeg = cam_.fovYDeg;
    s.texelSizeIsAbsolute = ortho || cascades;
    s.texelSize = ortho || cascades ? frame.wsLength(cam_.texelScale) : cam_.texelScale;
    return s;
}

// Texel sizes as stored by a typical implementation (24-bit depth padded to 32).
uint64_t ShadowMapLight::memoryBytes() const {
    const uint64_t texels = uint64_t(technique_.resolution()) * uint64_t(technique_.resolution());
    const uint64_t depthBytes = technique_.depthBits() == 16 ? 2 : 4;
    if (technique_.storage() != MapStorage::Moments)
        return texels * depthBytes * uint64_t(cam_.faces);
    // The moment map (RGBA32F per face), and one face's depth buffer and, with a blur, its
    // moments and blur target; a cube map's blur, its six padded faces, (side + 2 radius)² texels,
    // and one of side x (side + 2 radius).
    const uint64_t res = uint64_t(technique_.resolution()),
                   padded = res + 2 * uint64_t(technique_.blurRadius());
    const uint64_t blurBytes = technique_.blurRadius() == 0 ? 0
                               : cubeBlur_                  ? (6 * padded + res) * padded * 16
                                                            : texels * (16 + 16);
    return texels * 16 * uint64_t(cam_.faces) + texels * depthBytes + blurBytes;
}

}  // namespace

std::unique_ptr<LightTechnique> ShadowMapTechnique::setUp(const LightSetup& setup) const {
    return std::make_unique<ShadowMapLight>(*this, setup);
}

}  // namespace so
