#include "raster_compare/gl/context/gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/volumes/shadow_volume_geometry.h"

namespace so {

namespace {

constexpr int kFloatsPerVertex = 8;  // local position, face normal, alpha-mask uv

GLint glWrap(TextureWrap w) {
    switch (w) {
        case TextureWrap::ClampToEdge:
            return GL_CLAMP_TO_EDGE;
        case TextureWrap::MirroredRepeat:
            return GL_MIRRORED_REPEAT;
        case TextureWrap::Repeat:
        default:
            return GL_REPEAT;
    }
}

// One level, R32F: the CPU's float alphas exactly. Rows go up as given: the image's top row is
// GL's row 0, at t = 0, which is uv v = 0 (glTF's convention, core/scene.h): no flip.
GlTexture uploadAlpha(int width, int height, const float* alpha) {
    GlTexture t = makeTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, GL_R32F, width, height);
    glTextureSubImage2D(t.get(), 0, 0, 0, width, height, GL_RED, GL_FLOAT, alpha);
    return t;
}

}  // namespace

GpuScene::GpuScene(const Scene& scene) : scene_(scene), frame_(LocalFrame::fit(scene.wsBounds)) {
    if (!scene.wsBounds.empty()) {
        lsBounds_.extend(frame_.lsFromWs(scene.wsBounds.lo));
        lsBounds_.extend(frame_.lsFromWs(scene.wsBounds.hi));
    }
    std::vector<float> vertices;
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const MeshPrimitive& m = scene.meshes[mi];
        draws_.push_back({GLint(vertices.size() / kFloatsPerVertex), GLsizei(m.indices.size())});
        // Only a tested textured mask reads its uvs; a constant mask has none.
        const bool uvs = scene.alphaTested(mi) && m.alpha->texture >= 0;
        if (uvs && m.uvs.size() != m.wsPositions.size())
            throw std::invalid_argument("scene: mesh " + std::to_string(mi) + " has " +
                                        std::to_string(m.uvs.size()) + " uvs for " +
                                        std::to_string(m.wsPositions.size()) + " positions");
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k)
                p[k] = frame_.lsFromWs(m.wsPositions[m.indices[t + size_t(k)]]);
            glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
            const double len = glm::length(n);
            n = len > 0.0 ? n / len : glm::dvec3(0.0);  // degenerate: no fragments anyway
            for (int k = 0; k < 3; ++k) {
                const glm::vec2 uv = uvs ? m.uvs[m.indices[t + size_t(k)]] : glm::vec2(0.0f);
                vertices.insert(vertices.end(), {float(p[k].x), float(p[k].y), float(p[k].z),
                                                 float(n.x), float(n.y), float(n.z), uv.x, uv.y});
            }
        }
    }
    uploadVertices(vertices);
    uploadAlphaMasks();
}

void GpuScene::uploadVertices(const std::vector<float>& vertices) {
    vbo_ = makeBuffer();
    glNamedBufferStorage(vbo_.get(),
                         GLsizeiptr(std::max<size_t>(1, vertices.size()) * sizeof(float)),
                         vertices.empty() ? nullptr : vertices.data(), 0);
    vao_ = makeVertexArray();
    glVertexArrayVertexBuffer(vao_.get(), 0, vbo_.get(), 0, kFloatsPerVertex * sizeof(float));
    const GLint sizes[3] = {3, 3, 2};
    const GLuint offsets[3] = {0, 3, 6};
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(vao_.get(), a);
        glVertexArrayAttribFormat(vao_.get(), a, sizes[a], GL_FLOAT, GL_FALSE,
                                  offsets[a] * sizeof(float));
        glVertexArrayAttribBinding(vao_.get(), a, 0);
    }
}

// One texture per AlphaTexture (only when some mesh is tested), and per tested mesh its mask.
void GpuScene::uploadAlphaMasks() {
    alpha_.resize(scene_.meshes.size());
    for (size_t m = 0; m < scene_.meshes.size(); ++m) anyAlphaTested_ |= scene_.alphaTested(m);
    if (!anyAlphaTested_) return;
    for (const AlphaTexture& t : scene_.alphaTextures) {
        if (t.alpha.size() != size_t(t.width) * size_t(t.height))
            throw std::invalid_argument(
                "scene: an alpha texture has " + std::to_string(t.alpha.size()) + " values for " +
                std::to_string(t.width) + " x " + std::to_string(t.height) + " texels");
        alphaTextures_.push_back(uploadAlpha(t.width, t.height, t.alpha.data()));
    }
    const float one = 1.0f;
    alphaTextures_.push_back(uploadAlpha(1, 1, &one));
    for (size_t m = 0; m < scene_.meshes.size(); ++m) {
        if (!scene_.alphaTested(m)) continue;
        const AlphaMask& mask = *scene_.meshes[m].alpha;
        if (mask.texture >= int(scene_.alphaTextures.size()))
            throw std::invalid_argument("scene: mesh " + std::to_string(m) +
                                        "'s alpha mask names texture " +
                                        std::to_string(mask.texture) + " of " +
                                        std::to_string(scene_.alphaTextures.size()));
        const size_t texture = mask.texture >= 0 ? size_t(mask.texture) : alphaTextures_.size() - 1;
        alpha_[m] = MeshAlpha{alphaTextures_[texture].get(), samplerFor(mask), mask.cutoff,
                              mask.factor, mask.filter == TextureFilter::Bilinear ? 4 : 1};
    }
}

// GL_NEAREST or GL_LINEAR for both minification and magnification: one level, no mipmaps, as
// core/alpha_mask.h samples.
GLuint GpuScene::samplerFor(const AlphaMask& mask) {
    const uint32_t key =
        uint32_t(mask.wrapS) | uint32_t(mask.wrapT) << 8 | uint32_t(mask.filter) << 16;
    for (size_t i = 0; i < samplerKeys_.size(); ++i)
        if (samplerKeys_[i] == key) return samplers_[i].get();
    GlSampler s = makeSampler();
    const GLint filter = mask.filter == TextureFilter::Bilinear ? GL_LINEAR : GL_NEAREST;
    glSamplerParameteri(s.get(), GL_TEXTURE_MIN_FILTER, filter);
    glSamplerParameteri(s.get(), GL_TEXTURE_MAG_FILTER, filter);
    glSamplerParameteri(s.get(), GL_TEXTURE_WRAP_S, glWrap(mask.wrapS));
    glSamplerParameteri(s.get(), GL_TEXTURE_WRAP_T, glWrap(mask.wrapT));
    samplerKeys_.push_back(key);
    samplers_.push_back(std::move(s));
    return samplers_.back().get();
}

GpuScene::~GpuScene() = default;

const WeldedScene& GpuScene::welded() const {
    if (!welded_) welded_ = std::make_unique<WeldedScene>(WeldedScene::build(scene_, frame_));
    return *welded_;
}

glm::dmat4 GpuScene::wsFromLs() const {
    return glm::scale(glm::translate(glm::dmat4(1.0), frame_.wsCenter),
                      glm::dvec3(std::ldexp(1.0, frame_.exponent)));
}

void GpuScene::bind() const {
    glBindVertexArray(vao_.get());
}

void GpuScene::setAlphaTest(GLuint program, size_t mesh) const {
    if (!anyAlphaTested_) return;  // the programs carry no test (alphaDefines)
    const std::optional<MeshAlpha>& a = alpha_[mesh];
    setInt(program, "u_alphaTested", a ? 1 : 0);
    if (!a) return;
    setFloat(program, "u_alphaCutoff", double(a->cutoff));
    setFloat(program, "u_alphaFactor", double(a->factor));
    setInt(program, "u_alphaTapTexels", a->tapTexels);  // a counting build's only
    glBindTextureUnit(kAlphaTextureUnit, a->texture);
    glBindSampler(kAlphaTextureUnit, a->sampler);
}

void GpuScene::drawMesh(GLuint program, size_t mesh) const {
    setAlphaTest(program, mesh);
    glDrawArrays(GL_TRIANGLES, draws_[mesh].first, draws_[mesh].count);
}

void GpuScene::draw(GLuint program, bool setMeshId) const {
    for (size_t i = 0; i < draws_.size(); ++i) {
        if (setMeshId) setFloat(program, "u_meshId", double(i));
        drawMesh(program, i);
    }
}

}  // namespace so
