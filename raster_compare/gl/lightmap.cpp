#include "raster_compare/gl/lightmap.h"

#include <chrono>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include "raster_compare/gl/camera_pass.h"
#include "raster_compare/gl/gl_program.h"
#include "raster_compare/gl/gpu_scene.h"
#include "raster_compare/gl/pass_timer.h"
#include "raster_compare/gl/shaders.h"

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

class LightmapLight final : public LightTechnique {
  public:
    LightmapLight(const LightmapSettings& settings, const LightSetup& setup);
    std::vector<std::string> passNames() const override { return {"visibility"}; }
    void renderLightPasses(PassClock&) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override { return atlasBytes_ + tableBytes_; }

  private:
    void uploadTable(const LightmapAtlas& atlas);
    void buildProgram(const LightmapSettings& settings, const CameraPass& camera);

    const Light& light_;
    const GpuScene& scene_;
    BakedLightmap baked_;
    GlBuffer texelFromLocal_, meshFirstTriangle_;
    GlProgram program_;
    uint64_t atlasBytes_ = 0, tableBytes_ = 0;
    double bakeMs_ = 0.0;
    std::map<std::string, int64_t> counts_;
};

LightmapLight::LightmapLight(const LightmapSettings& settings, const LightSetup& setup)
    : light_(setup.light), scene_(setup.scene) {
    // The bake's wall time, from the charts to the atlas stored, the GL finished.
    const auto t0 = std::chrono::steady_clock::now();
    const LightmapAtlas atlas = buildLightmapAtlas(scene_.scene(), settings.atlas);
    const double chartsMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    baked_ = bakeLightmap(light_, scene_, atlas, settings.bake);
    uploadTable(atlas);
    glFinish();
    bakeMs_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    baked_.passMs["bake.charts"] = chartsMs;  // CPU: the charts and their packing
    atlasBytes_ = atlas.texels();             // GL_R8: a byte a texel
    counts_ = {{"atlas_width", atlas.width},
               {"atlas_height", atlas.height},
               {"atlas_bytes", int64_t(atlasBytes_)},
               {"charts", int64_t(atlas.charts.size())},
               {"texcoord1_meshes", int64_t(atlas.texcoord1Meshes)},
               {"baked_triangles", int64_t(atlas.bakedTriangles)},
               {"dynamic_casters_left_out", int64_t(atlas.dynamicMeshes)},
               {"dynamic_triangles_left_out", int64_t(atlas.dynamicTriangles)},
               {"bake_samples", baked_.samples},
               {"bake_peak_bytes", int64_t(baked_.peakBytes)},
               {"texels_covered", int64_t(baked_.texelsCovered)},
               {"texels_from_centroids", int64_t(baked_.texelsFromCentroids)},
               {"texels_dilated",
                int64_t(baked_.texelsFilled - baked_.texelsCovered - baked_.texelsFromCentroids)}};
    buildProgram(settings, setup.camera);
}

// Per triangle of every baked mesh its two rows, and per mesh the index of its first triangle
// (-1 for a mesh not baked).
void LightmapLight::uploadTable(const LightmapAtlas& atlas) {
    const Scene& scene = scene_.scene();
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
                    glm::vec3(scene_.frame().lsFromWs(m.wsPositions[m.indices[3 * t + k]])));
            glm::vec4 r0, r1;
            texelRows(p, atlas.corners[mi][t], r0, r1);
            rows.push_back(r0);
            rows.push_back(r1);
        }
    }
    if (rows.empty()) rows.resize(2, glm::vec4(0.0f));
    texelFromLocal_ = makeBuffer();
    glNamedBufferStorage(texelFromLocal_.get(), GLsizeiptr(rows.size() * sizeof(glm::vec4)),
                         rows.data(), 0);
    meshFirstTriangle_ = makeBuffer();
    glNamedBufferStorage(meshFirstTriangle_.get(), GLsizeiptr(first.size() * sizeof(int32_t)),
                         first.data(), 0);
    tableBytes_ = rows.size() * sizeof(glm::vec4) + first.size() * sizeof(int32_t);
}

void LightmapLight::buildProgram(const LightmapSettings& settings, const CameraPass& camera) {
    const std::string lightKind = light_.type == LightType::Directional ? "#define LIGHT_ORTHO\n"
                                  : light_.type == LightType::Spot      ? "#define LIGHT_SPOT\n"
                                                                        : "";
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
    glBindTextureUnit(0, baked_.atlas.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, texelFromLocal_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, meshFirstTriangle_.get());
    scene_.draw(program_.get(), true);
    clock.end();
}

RasterLightStats LightmapLight::describe() const {
    RasterLightStats s;
    s.counts = counts_;
    s.bakeMs = bakeMs_;
    s.bakePassMs = baked_.passMs;
    return s;
}

}  // namespace

std::unique_ptr<LightTechnique> setUpLightmap(const LightmapSettings& settings,
                                              const LightSetup& setup) {
    return std::make_unique<LightmapLight>(settings, setup);
}

}  // namespace so
