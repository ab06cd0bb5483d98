#include "raster_compare/gl/lightmaps/lightmap.h"

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "core/error.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {
namespace {

// The affine map from a triangle's local points to its atlas texels: rows r0 and r1 with
// texel = (r0 . (p, 1), r1 . (p, 1)), exact at the three corners and constant along the normal
// (so a point a rounding error off the plane maps where its projection does). Zero for a triangle
// with no area.
void texelRows(const glm::dvec3 (&p)[3], const std::array<glm::dvec2, 3>& texel, glm::vec4& r0,
               glm::vec4& r1) {
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const double a = glm::dot(e1, e1), b = glm::dot(e1, e2), c = glm::dot(e2, e2);
    const double det = a * c - b * b;
    r0 = r1 = glm::vec4(0.0f);
    if (!(det > 0.0)) return;
    for (int j = 0; j < 2; ++j) {
        const double d1 = texel[1][j] - texel[0][j], d2 = texel[2][j] - texel[0][j];
        const glm::dvec3 g = ((c * d1 - b * d2) / det) * e1 + ((a * d2 - b * d1) / det) * e2;
        (j == 0 ? r0 : r1) = glm::vec4(glm::vec3(g), float(texel[0][j] - glm::dot(g, p[0])));
    }
}

// One light's bake and the atlas's lookup table: made once per render by the first of the
// technique's instances to set the light up (the counted frame's, when work is counted), under
// CountingPaused so that its programs are the ordinary ones, and taken over by the next (the timed
// instance) through LightSetup::shared. It was baked twice before (issue 44): the same atlas,
// seconds per area light (64 cube maps of 2048^2).
struct LightmapBake final : SetUpShared {
    BakedLightmap baked;
    GlBuffer texelFromLocal, meshFirstTriangle;
    uint64_t atlasBytes = 0, tableBytes = 0;
    double bakeMs = 0.0;
    std::map<std::string, int64_t> counts;
};

// Per triangle of every baked mesh its two rows, and per mesh the index of its first triangle
// (-1 for a mesh not baked).
void uploadTable(const GpuScene& gpu, const LightmapAtlas& atlas, LightmapBake& out) {
    const Scene& scene = gpu.scene();
    std::vector<glm::vec4> rows;
    std::vector<int32_t> first(std::max<size_t>(1, scene.meshes.size()), -1);
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const MeshPrimitive& m = scene.meshes[mi];
        if (m.dynamic) continue;
        first[mi] = int32_t(rows.size() / 2);
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            // The positions as GpuScene uploads them (float), so the lookup is exact there.
            glm::dvec3 p[3];
            for (size_t k = 0; k < 3; ++k)
                p[k] = glm::dvec3(
                    glm::vec3(gpu.frame().lsFromWs(m.wsPositions[m.indices[3 * t + k]])));
            glm::vec4 r0, r1;
            texelRows(p, atlas.corners[mi][t], r0, r1);
            rows.push_back(r0);
            rows.push_back(r1);
        }
    }
    if (rows.empty()) rows.resize(2, glm::vec4(0.0f));
    out.texelFromLocal = makeBuffer();
    glNamedBufferStorage(out.texelFromLocal.get(), GLsizeiptr(rows.size() * sizeof(glm::vec4)),
                         rows.data(), 0);
    out.meshFirstTriangle = makeBuffer();
    glNamedBufferStorage(out.meshFirstTriangle.get(), GLsizeiptr(first.size() * sizeof(int32_t)),
                         first.data(), 0);
    out.tableBytes = rows.size() * sizeof(glm::vec4) + first.size() * sizeof(int32_t);
}

std::shared_ptr<const LightmapBake> bake(const LightmapSettings& settings, const Light& light,
                                         const GpuScene& gpu) {
    const CountingPaused ordinaryPrograms;
    auto out = std::make_shared<LightmapBake>();
    // The bake's wall time, from the charts to the atlas stored, the GL finished.
    const auto t0 = std::chrono::steady_clock::now();
    const LightmapAtlas atlas = buildLightmapAtlas(gpu.scene(), settings.atlas);
    const double chartsMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    out->baked = bakeLightmap(light, gpu, atlas, settings.bake);
    uploadTable(gpu, atlas, *out);
    glFinish();
    out->bakeMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const BakedLightmap& b = out->baked;
    out->baked.passMs["bake.charts"] = chartsMs;  // CPU: the charts and their packing
    out->atlasBytes = atlas.texels();             // GL_R8: a byte a texel
    out->counts = {
        {"atlas_width", atlas.width},
        {"atlas_height", atlas.height},
        {"atlas_bytes", int64_t(out->atlasBytes)},
        {"charts", int64_t(atlas.charts.size())},
        {"texcoord1_meshes", int64_t(atlas.texcoord1Meshes)},
        {"baked_triangles", int64_t(atlas.bakedTriangles)},
        {"dynamic_casters_left_out", int64_t(atlas.dynamicMeshes)},
        {"dynamic_triangles_left_out", int64_t(atlas.dynamicTriangles)},
        {"bake_samples", b.samples},
        {"bake_peak_bytes", int64_t(b.peakBytes)},
        {"texels_covered", int64_t(b.texelsCovered)},
        {"texels_from_centroids", int64_t(b.texelsFromCentroids)},
        {"texels_dilated", int64_t(b.texelsFilled - b.texelsCovered - b.texelsFromCentroids)}};
    return out;
}

// The light's bake from an earlier instance of this render, or a new one left for the next.
std::shared_ptr<const LightmapBake> sharedBake(const LightmapSettings& settings,
                                               const LightSetup& setup) {
    if (setup.shared) {
        const auto it = setup.shared->find(setup.light.name);
        if (it != setup.shared->end()) {
            auto found = std::dynamic_pointer_cast<const LightmapBake>(it->second);
            SO_CHECK(found != nullptr);
            return found;
        }
    }
    std::shared_ptr<const LightmapBake> made = bake(settings, setup.light, setup.scene);
    if (setup.shared) (*setup.shared)[setup.light.name] = made;
    return made;
}

class LightmapLight final : public LightTechnique {
  public:
    LightmapLight(const LightmapSettings& settings, const LightSetup& setup)
        : light_(setup.light), scene_(setup.scene), bake_(sharedBake(settings, setup)) {
        buildProgram(settings, setup.camera);
    }
    std::vector<std::string> passNames() const override { return {"visibility"}; }
    void renderLightPasses(PassClock&) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override { return bake_->atlasBytes + bake_->tableBytes; }

  private:
    void buildProgram(const LightmapSettings& settings, const CameraPass& camera);

    const Light& light_;
    const GpuScene& scene_;
    std::shared_ptr<const LightmapBake> bake_;
    GlProgram program_;
};

void LightmapLight::buildProgram(const LightmapSettings& settings, const CameraPass& camera) {
    const std::string lightKind = lightCameraDefines(light_);
    program_ =
        so::buildProgram(scene_.alphaDefines() + lightKind + settings.defines, shaders::scene_vert,
                         {shaders::alpha_test_glsl, shaders::lightmap_frag, settings.glsl});
    const GLuint p = program_.get();
    const LocalFrame& frame = scene_.frame();
    setMat4(p, "u_clipFromLocal", camera.clipFromLocal());
    setVec3(p, "u_lsEye", camera.lsEye());
    setFloat(p, "u_pixelScale", camera.pixelScale());
    setVec3(p, "u_lsLightPosition", frame.lsFromWs(light_.wsPosition));
    setVec3(p, "u_lsLightDirection", glm::normalize(light_.wsDirection));
    setFloat(p, "u_cosOuter", std::cos(light_.outerConeDeg * 3.14159265358979323846 / 180.0));
    setFloat(p, "u_lsTexel", frame.lsLength(1.0 / settings.atlas.texelsPerUnit));
}

void LightmapLight::renderVisibility(PassClock& clock) {
    clock.begin("visibility");
    glUseProgram(program_.get());
    glBindTextureUnit(0, bake_->baked.atlas.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bake_->texelFromLocal.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bake_->meshFirstTriangle.get());
    scene_.draw(program_.get(), true);
    clock.end();
}

RasterLightStats LightmapLight::describe() const {
    RasterLightStats s;
    s.counts = bake_->counts;
    s.bakeMs = bake_->bakeMs;
    s.bakePassMs = bake_->baked.passMs;
    return s;
}

}  // namespace

std::unique_ptr<LightTechnique> setUpLightmap(const LightmapSettings& settings,
                                              const LightSetup& setup) {
    return std::make_unique<LightmapLight>(settings, setup);
}

}  // namespace so
