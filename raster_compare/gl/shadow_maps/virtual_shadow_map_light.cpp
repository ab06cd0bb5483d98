#include "raster_compare/gl/shadow_maps/virtual_shadow_map_light.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include <glm/ext/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "core/error.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {
namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;
constexpr uint64_t kPoolTexelBytes = 4;  // GL_DEPTH_COMPONENT32F

std::vector<double> powersOfTwo(int lo, int hi) {
    std::vector<double> v;
    for (int p = lo; p <= hi; p *= 2) v.push_back(p);
    return v;
}

}  // namespace

ParamTable VirtualMapSettings::params(const std::string& needs, bool poolIsQuality) {
    ParamTable p = {
        {"virtual_size", 65536, 256, 65536, true, "side of the virtual map's level 0 in texels",
         powersOfTwo(256, 65536)},
        {"page_size", 128, 32, 1024, true, "side of a page in texels (at most virtual_size)",
         powersOfTwo(32, 1024)},
        {"pool_mb",
         16,
         1,
         1024,
         true,
         "memory of the physical page pool in MiB (32-bit depth): the largest about square grid "
         "of pages that fits",
         {},
         poolIsQuality},
        {"density", 1.0, 1.0 / 64.0, 1024.0, false,
         "texels wanted across a pixel's footprint (at n.l): pages are asked for at the coarsest "
         "level with predicted aliasing <= 1/density"},
        methodParam("refine", 1, {"off", "on"},
                    "on: when the pool cannot hold every page asked for, fill half of it first, "
                    "then ask for finer pages only near the shadow edges found there; off: by "
                    "footprint alone"),
    };
    if (needs.empty()) return p;
    for (ParamSpec& s : p) {
        s.needs = needs;
        s.doc = needs + ": " + s.doc;  // the tables in docs/ show no `needs` column
    }
    return p;
}

VirtualMapSettings::VirtualMapSettings(const ParamValues& v, const std::string& name)
    : technique(name),
      layout{v.integer("virtual_size"), v.integer("page_size")},
      poolMb(v.integer("pool_mb")),
      density(v.real("density")),
      refine(v.integer("refine") == 1) {
    const std::string file = "technique " + technique;
    if (layout.pageSize > layout.virtualSize)
        throwInputError(file, "page_size",
                        "page_size " + std::to_string(layout.pageSize) +
                            " is larger than virtual_size " + std::to_string(layout.virtualSize));
    // The pool: the largest grid of pages within the budget that is about square.
    const uint64_t fit = uint64_t(poolMb) * kMiB /
                         (uint64_t(layout.pageSize) * uint64_t(layout.pageSize) * kPoolTexelBytes);
    poolColumns = int(std::floor(std::sqrt(double(fit))));
    poolRows = poolColumns > 0 ? int(fit / uint64_t(poolColumns)) : 0;
    if (poolPages() < 1)
        throwInputError(file, "pool_mb",
                        "a pool of " + std::to_string(poolMb) + " MiB holds no page of " +
                            std::to_string(layout.pageSize) + "^2 32-bit texels");
}

int VirtualMapSettings::cubeResolution() const {
    // Six faces of 4-byte texels.
    const double side = std::sqrt(double(uint64_t(poolMb) * kMiB) / 24.0);
    return std::clamp(int(side), 16, 16384);
}

std::string settingText(const std::string& key, double v) {
    std::ostringstream s;
    s.precision(17);
    s << key << "=" << v;
    return s.str();
}

namespace {

// A directional or spot light: the virtual map and its passes.
class VirtualMapLight final : public LightTechnique {
  public:
    VirtualMapLight(const VirtualMapSettings& settings, const SlopeBias& bias,
                    VirtualVisibility visibility, const LightSetup& setup, const LightCamera& cam);
    std::vector<std::string> passNames() const override {
        return {"mark", "pages", "refine", "visibility"};
    }
    void renderLightPasses(PassClock& clock) override;
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override;

  private:
    // A mesh's footprint on the virtual map, in normalised device coordinates.
    struct NdcRect {
        glm::dvec2 lo, hi;
    };
    void createTargets();
    void createPrograms(const LightSetup& setup);
    void setShadingUniforms(GLuint program) const;
    void computeMeshRects();
    void renderMarkDepth();
    std::vector<uint32_t> markPages(GLuint markProgram);
    void uploadTable();
    void renderPages(size_t first);

    const VirtualMapSettings& map_;
    const SlopeBias& bias_;
    const VirtualVisibility visibility_;
    const GpuScene& scene_;
    const CameraPass& camera_;
    LightCamera cam_;
    GlTexture markDepth_, requests_, pageTable_, pool_;
    GlFramebuffer markFbo_, poolFbo_;
    GlProgram depthProg_, markProg_, edgesProg_, visibilityProg_;
    std::vector<NdcRect> meshRects_;
    PageAllocation allocation_;       // the last frame's
    int64_t footprintRequested_ = 0;  // the last frame's requests before edge refinement
    int64_t meshDraws_ = 0;           // the last frame's page draws of a mesh
};

VirtualMapLight::VirtualMapLight(const VirtualMapSettings& settings, const SlopeBias& bias,
                                 VirtualVisibility visibility, const LightSetup& setup,
                                 const LightCamera& cam)
    : map_(settings),
      bias_(bias),
      visibility_(std::move(visibility)),
      scene_(setup.scene),
      camera_(setup.camera),
      cam_(cam) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int poolSide = std::max(map_.poolColumns, map_.poolRows) * map_.layout.pageSize;
    if (poolSide > maxSize)
        throwInputError("technique " + map_.technique, "pool_mb",
                        "the pool's side of " + std::to_string(poolSide) +
                            " texels exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize));
    createTargets();
    createPrograms(setup);
    computeMeshRects();
}

void VirtualMapLight::createTargets() {
    markDepth_ = makeTexture2D(GL_DEPTH_COMPONENT32F, camera_.width(), camera_.height());
    markFbo_ = makeFramebuffer();
    glNamedFramebufferTexture(markFbo_.get(), GL_DEPTH_ATTACHMENT, markDepth_.get(), 0);
    glNamedFramebufferDrawBuffer(markFbo_.get(), GL_NONE);
    const int tw = map_.layout.tableWidth(), th = map_.layout.tableHeight();
    requests_ = makeTexture2D(GL_R32UI, tw, th);
    pageTable_ = makeTexture2D(GL_R32I, tw, th);
    const int ps = map_.layout.pageSize;
    pool_ = makeTexture2D(GL_DEPTH_COMPONENT32F, map_.poolColumns * ps, map_.poolRows * ps);
    poolFbo_ = makeFramebuffer();
    glNamedFramebufferTexture(poolFbo_.get(), GL_DEPTH_ATTACHMENT, pool_.get(), 0);
    glNamedFramebufferDrawBuffer(poolFbo_.get(), GL_NONE);
}

void VirtualMapLight::createPrograms(const LightSetup& setup) {
    depthProg_ = buildProgram(scene_.alphaDefines(), shaders::scene_vert,
                              {shaders::alpha_test_glsl, shaders::depth_frag});
    const std::string defines =
        scene_.alphaDefines() +
        std::string(cam_.kind == LightCamera::Kind::Ortho ? "#define LIGHT_ORTHO\n"
                                                          : "#define LIGHT_SPOT\n") +
        "#define VIRTUAL_SIZE " + std::to_string(map_.layout.virtualSize) + "\n#define PAGE_SIZE " +
        std::to_string(map_.layout.pageSize) + "\n#define LEVELS " +
        std::to_string(map_.layout.levels()) + "\n#define POOL_COLUMNS " +
        std::to_string(map_.poolColumns) + "\n" + glslDefine("DENSITY", map_.density) +
        bias_.defines() + "#define TABLE_TEXEL_BYTES " +
        std::to_string(texelBytes(pageTable_.get())) + "\n#define POOL_TEXEL_BYTES " +
        std::to_string(texelBytes(pool_.get())) + "\n";
    markProg_ = buildProgram(
        defines, shaders::scene_vert,
        {shaders::alpha_test_glsl, shaders::adaptive_glsl, shaders::adaptive_mark_frag});
    // The edge test looks two texels around the pixel's: a coarse page's edge lies within about a
    // texel of the true one, so a pixel whose 5 x 5 texels agree is settled.
    edgesProg_ = buildProgram(
        defines + "#define MARK_EDGES\n#define EDGE_RADIUS 2\n", shaders::scene_vert,
        {shaders::alpha_test_glsl, shaders::adaptive_glsl, shaders::adaptive_mark_frag});
    std::vector<const char*> sources = {shaders::alpha_test_glsl, shaders::adaptive_glsl};
    sources.insert(sources.end(), visibility_.includes.begin(), visibility_.includes.end());
    sources.push_back(visibility_.frag);
    visibilityProg_ = buildProgram(defines + visibility_.defines, shaders::scene_vert, sources);
    for (GLuint p : {markProg_.get(), edgesProg_.get(), visibilityProg_.get()}) {
        setShadingUniforms(p);
        setInt(p, "u_pageTable", 0);
        setInt(p, "u_pool", 1);
    }
    if (visibility_.setUniforms) visibility_.setUniforms(visibilityProg_.get(), setup);
}

void VirtualMapLight::setShadingUniforms(GLuint p) const {
    setLightCameraUniforms(p, camera_, cam_);
    std::vector<GLint> rows;
    for (int l = 0; l < map_.layout.levels(); ++l) rows.push_back(map_.layout.tableRow(l));
    glProgramUniform1iv(p, glGetUniformLocation(p, "u_levelRow"), GLsizei(rows.size()),
                        rows.data());
}

// Each mesh's light-space bounds projected on the map; a mesh with a corner behind a spot light
// (w <= 0) may cover any page.
void VirtualMapLight::computeMeshRects() {
    const Scene& scene = scene_.scene();
    const glm::dmat4 clipFromLocal = cam_.clipFromLocal(0);
    for (const MeshPrimitive& m : scene.meshes) {
        Bounds3d ls;
        for (const glm::dvec3& p : m.wsPositions) ls.extend(scene_.frame().lsFromWs(p));
        NdcRect r{glm::dvec2(1e300), glm::dvec2(-1e300)};
        for (int k = 0; k < 8 && !ls.empty(); ++k) {
            const glm::dvec4 c =
                clipFromLocal * glm::dvec4((k & 1) ? ls.hi.x : ls.lo.x, (k & 2) ? ls.hi.y : ls.lo.y,
                                           (k & 4) ? ls.hi.z : ls.lo.z, 1.0);
            if (c.w <= 1e-12) {
                r = {glm::dvec2(-1e300), glm::dvec2(1e300)};
                break;
            }
            r.lo = glm::min(r.lo, glm::dvec2(c) / c.w);
            r.hi = glm::max(r.hi, glm::dvec2(c) / c.w);
        }
        meshRects_.push_back(r);
    }
}

void VirtualMapLight::renderLightPasses(PassClock& clock) {
    clock.begin("mark");
    renderMarkDepth();
    const std::vector<uint32_t> pixels = markPages(markProg_.get());
    clock.end();
    clock.begin("pages");
    allocation_ = allocatePages(map_.layout, pixels, map_.poolPages());
    footprintRequested_ = allocation_.requested;
    const bool refine = map_.refine && allocation_.dropped > 0;
    if (refine) allocation_ = allocatePages(map_.layout, pixels, std::max(1, map_.poolPages() / 2));
    uploadTable();
    renderPages(0);
    clock.end();
    clock.begin("refine");
    if (refine) {
        const PageAllocation base = allocation_;
        const std::vector<uint32_t> edges = markPages(edgesProg_.get());
        allocation_ = allocatePages(map_.layout, edges, map_.poolPages(), &base);
        uploadTable();
        renderPages(base.pages.size());
    }
    clock.end();
}

void VirtualMapLight::uploadTable() {
    glTextureSubImage2D(pageTable_.get(), 0, 0, 0, map_.layout.tableWidth(),
                        map_.layout.tableHeight(), GL_RED_INTEGER, GL_INT,
                        allocation_.table.data());
}

// The camera's depth, so that the mark passes see only visible surfaces.
void VirtualMapLight::renderMarkDepth() {
    const float far = 0.0f;  // the camera's reversed depth
    glBindFramebuffer(GL_FRAMEBUFFER, markFbo_.get());
    glViewport(0, 0, camera_.width(), camera_.height());
    glClearNamedFramebufferfv(markFbo_.get(), GL_DEPTH, 0, &far);
    glDepthFunc(GL_GREATER);
    glUseProgram(depthProg_.get());
    setMat4(depthProg_.get(), "u_clipFromLocal", camera_.clipFromLocal());
    scene_.draw(depthProg_.get(), false);
}

// The camera's visible lit pixels counted into the pages they need (the edge program: those the
// resident pages do not settle), read back. Over renderMarkDepth's depth.
std::vector<uint32_t> VirtualMapLight::markPages(GLuint markProgram) {
    const uint32_t zero = 0;
    glClearTexImage(requests_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindFramebuffer(GL_FRAMEBUFFER, markFbo_.get());
    glViewport(0, 0, camera_.width(), camera_.height());
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
    glUseProgram(markProgram);
    glBindImageTexture(0, requests_.get(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindTextureUnit(0, pageTable_.get());
    glBindTextureUnit(1, pool_.get());
    scene_.draw(markProgram, false);
    glDepthMask(GL_TRUE);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    std::vector<uint32_t> pixels(size_t(map_.layout.tableWidth()) *
                                 size_t(map_.layout.tableHeight()));
    glGetTextureImage(requests_.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      GLsizei(pixels.size() * sizeof(uint32_t)), pixels.data());
    return pixels;
}

// The light's clip space cropped to one page: that page's square of normalised device
// coordinates mapped onto [-1, 1]^2 (x' = n x - (2 i + 1 - n) w, so perspective divides alike).
glm::dmat4 pageFromClip(int pagesPerSide, int x, int y) {
    const double n = pagesPerSide;
    glm::dmat4 m(1.0);
    m[0][0] = n;
    m[1][1] = n;
    m[3][0] = -(2.0 * x + 1.0 - n);
    m[3][1] = -(2.0 * y + 1.0 - n);
    return m;
}

// Renders the allocation's pages from `first` on.
void VirtualMapLight::renderPages(size_t first) {
    const int ps = map_.layout.pageSize;
    const float one = 1.0f;
    glBindFramebuffer(GL_FRAMEBUFFER, poolFbo_.get());
    glUseProgram(depthProg_.get());
    glDepthFunc(GL_LESS);
    glEnable(GL_SCISSOR_TEST);
    const glm::dmat4 lightClipFromLocal = cam_.clipFromLocal(0);
    if (first == 0) meshDraws_ = 0;
    for (size_t i = first; i < allocation_.pages.size(); ++i) {
        const PageSlot& page = allocation_.pages[i];
        const int ox = (page.slot % map_.poolColumns) * ps,
                  oy = (page.slot / map_.poolColumns) * ps;
        glViewport(ox, oy, ps, ps);
        glScissor(ox, oy, ps, ps);
        glClearNamedFramebufferfv(poolFbo_.get(), GL_DEPTH, 0, &one);
        const int n = map_.layout.pagesPerSide(page.level);
        setMat4(depthProg_.get(), "u_clipFromLocal",
                pageFromClip(n, page.x, page.y) * lightClipFromLocal);
        // The page's square in normalised device coordinates, against each mesh's.
        const glm::dvec2 lo = glm::dvec2(-1.0 + 2.0 * page.x / n, -1.0 + 2.0 * page.y / n);
        const glm::dvec2 hi = lo + 2.0 / n;
        for (size_t m = 0; m < meshRects_.size(); ++m) {
            const NdcRect& r = meshRects_[m];
            if (r.hi.x < lo.x || r.hi.y < lo.y || r.lo.x > hi.x || r.lo.y > hi.y) continue;
            scene_.drawMesh(depthProg_.get(), m);
            ++meshDraws_;
        }
    }
    glDisable(GL_SCISSOR_TEST);
}

void VirtualMapLight::renderVisibility(PassClock& clock) {
    clock.begin("visibility");
    glUseProgram(visibilityProg_.get());
    glBindTextureUnit(0, pageTable_.get());
    glBindTextureUnit(1, pool_.get());
    scene_.draw(visibilityProg_.get(), false);
    clock.end();
}

RasterLightStats VirtualMapLight::describe() const {
    const LocalFrame& frame = scene_.frame();
    RasterLightStats s;
    const bool ortho = cam_.kind == LightCamera::Kind::Ortho;
    s.map = ortho ? "orthographic" : "perspective";
    s.clipFromWorld = {cam_.clipFromLocal(0) * glm::inverse(scene_.wsFromLs())};
    s.wsNear = frame.wsLength(cam_.near);
    s.wsFar = frame.wsLength(cam_.far);
    s.fovYDeg = cam_.fovYDeg;
    // Level 0's texel: the finest the map can give.
    s.texelSizeIsAbsolute = ortho;
    s.texelSize = ortho ? frame.wsLength(cam_.texelScale) : cam_.texelScale;
    s.counts = {{"pages_marked", allocation_.marked},
                {"pages_requested_by_footprint", footprintRequested_},
                {"pages_requested", allocation_.requested},
                {"pages_rendered", int64_t(allocation_.pages.size())},
                {"pages_dropped", allocation_.dropped},
                {"finest_level_rendered", allocation_.finestLevel},
                {"levels", map_.layout.levels()},
                {"levels_marked", allocation_.levelsMarked},
                {"pool_pages", map_.poolPages()},
                {"page_mesh_draws", meshDraws_}};
    return s;
}

// The pool (32-bit depth), the request counts and the page table (32 bits a cell each), and the
// mark pass's depth buffer (32-bit float, the camera's size).
uint64_t VirtualMapLight::memoryBytes() const {
    const uint64_t ps = uint64_t(map_.layout.pageSize);
    const uint64_t cells = uint64_t(map_.layout.tableWidth()) * uint64_t(map_.layout.tableHeight());
    return uint64_t(map_.poolPages()) * ps * ps * kPoolTexelBytes + cells * 4 * 2 +
           uint64_t(camera_.width()) * uint64_t(camera_.height()) * 4;
}

// Point and area lights: the technique's plain counterpart (adaptive: slope-bias; smrt: smrt with
// map=plain) on a cube map of 32-bit depth in (about) the pool's memory, its passes
// ("shadow_map", "visibility") as that technique reports them.
class CubeFallbackLight final : public LightTechnique {
  public:
    CubeFallbackLight(const VirtualMapSettings& settings, const LightSetup& setup,
                      const CubeFallback& fallback, bool probes);
    std::vector<std::string> passNames() const override { return light_->passNames(); }
    void renderLightPasses(PassClock& clock) override { light_->renderLightPasses(clock); }
    void renderVisibility(PassClock& clock) override { light_->renderVisibility(clock); }
    bool probeDepth(bool on) override { return light_->probeDepth(on); }
    std::optional<DepthComparison> readDepthComparison(const LightTarget& own) const override {
        return light_->readDepthComparison(own);
    }
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override { return light_->memoryBytes(); }

  private:
    int resolution_;
    std::unique_ptr<Technique> plain_;  // outlives light_, which refers to it
    std::unique_ptr<LightTechnique> light_;
};

CubeFallbackLight::CubeFallbackLight(const VirtualMapSettings& settings, const LightSetup& setup,
                                     const CubeFallback& fallback, bool probes)
    : resolution_(settings.cubeResolution()), plain_(fallback(resolution_)) {
    // The depth probe only where the owner's target has one (adaptive's has none).
    LightSetup own = setup;
    own.depthProbe = setup.depthProbe && probes;
    light_ = plain_->setUp(own);
}

RasterLightStats CubeFallbackLight::describe() const {
    RasterLightStats s = light_->describe();
    s.counts["cube_fallback"] = 1;
    s.counts["cube_resolution"] = resolution_;
    return s;
}

}  // namespace

std::unique_ptr<LightTechnique> setUpVirtualShadowMap(
    const VirtualMapSettings& settings, const SlopeBias& bias, VirtualVisibility visibility,
    const LightSetup& setup, const CubeFallback& fallback, bool fallbackProbes) {
    const LightCamera cam = fitLightCamera(setup.light, setup.scene.frame(), setup.scene.lsBounds(),
                                           settings.layout.virtualSize,
                                           setup.lsReceivers ? &*setup.lsReceivers : nullptr);
    if (cam.kind == LightCamera::Kind::Cube)
        return std::make_unique<CubeFallbackLight>(settings, setup, fallback, fallbackProbes);
    return std::make_unique<VirtualMapLight>(settings, bias, std::move(visibility), setup, cam);
}

}  // namespace so
