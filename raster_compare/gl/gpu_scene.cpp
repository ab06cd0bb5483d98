#include "raster_compare/gl/gpu_scene.h"

#include <algorithm>
#include <cmath>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "raster_compare/gl/gl_program.h"
#include "raster_compare/gl/shadow_volume_geometry.h"

namespace so {

GpuScene::GpuScene(const Scene& scene) : scene_(scene), frame_(LocalFrame::fit(scene.wsBounds)) {
    if (!scene.wsBounds.empty()) {
        lsBounds_.extend(frame_.lsFromWs(scene.wsBounds.lo));
        lsBounds_.extend(frame_.lsFromWs(scene.wsBounds.hi));
    }
    std::vector<float> vertices;
    for (const MeshPrimitive& m : scene.meshes) {
        draws_.push_back({GLint(vertices.size() / 6), GLsizei(m.indices.size())});
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k)
                p[k] = frame_.lsFromWs(m.wsPositions[m.indices[t + size_t(k)]]);
            glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
            const double len = glm::length(n);
            n = len > 0.0 ? n / len : glm::dvec3(0.0);  // degenerate: no fragments anyway
            for (int k = 0; k < 3; ++k)
                vertices.insert(vertices.end(), {float(p[k].x), float(p[k].y), float(p[k].z),
                                                 float(n.x), float(n.y), float(n.z)});
        }
    }
    vbo_ = makeBuffer();
    glNamedBufferStorage(vbo_.get(),
                         GLsizeiptr(std::max<size_t>(1, vertices.size()) * sizeof(float)),
                         vertices.empty() ? nullptr : vertices.data(), 0);
    vao_ = makeVertexArray();
    glVertexArrayVertexBuffer(vao_.get(), 0, vbo_.get(), 0, 6 * sizeof(float));
    for (GLuint a = 0; a < 2; ++a) {
        glEnableVertexArrayAttrib(vao_.get(), a);
        glVertexArrayAttribFormat(vao_.get(), a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao_.get(), a, 0);
    }
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

void GpuScene::drawMesh(size_t mesh) const {
    glDrawArrays(GL_TRIANGLES, draws_[mesh].first, draws_[mesh].count);
}

void GpuScene::draw(GLuint program, bool setMeshId) const {
    for (size_t i = 0; i < draws_.size(); ++i) {
        if (setMeshId) setFloat(program, "u_meshId", double(i));
        glDrawArrays(GL_TRIANGLES, draws_[i].first, draws_[i].count);
    }
}

}  // namespace so
