// The scene on the GPU: every triangle unshared, in the local frame (core/local_frame.h), each
// vertex carrying its face normal computed in double and its alpha-mask uv (zeros where the mesh
// has no mask), so gl_PrimitiveID is the triangle's index in its mesh. Every pass draws the scene
// through here, and so gets each alpha-tested mesh's mask set (shaders/alpha_test.glsl).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "raster_compare/gl/context/gl_object.h"

namespace so {

struct WeldedScene;

class GpuScene {
  public:
    explicit GpuScene(const Scene& scene);  // uploads; needs a current context
    ~GpuScene();

    const Scene& scene() const { return scene_; }
    const LocalFrame& frame() const { return frame_; }
    const Bounds3d& lsBounds() const { return lsBounds_; }
    glm::dmat4 wsFromLs() const;

    // Binds the vertex array (once per render: every pass uses it).
    void bind() const;
    // Draws every mesh with `program` (bound by the caller), setting per mesh its alpha test and,
    // when asked, its u_meshId uniform.
    void draw(GLuint program, bool setMeshId) const;
    // Draws one mesh with `program` (bound by the caller), its alpha test set.
    void drawMesh(GLuint program, size_t mesh) const;
    size_t meshCount() const { return draws_.size(); }

    // The #defines of every program that draws the scene with a frame that calls alphaTest()
    // (shaders/alpha_test.glsl): "#define ALPHA_TEST_OFF\n" when no mesh is alpha-tested, so a
    // scene without masks runs shaders with no discard (a GPU keeps its early depth test), else "".
    const char* alphaDefines() const { return anyAlphaTested_ ? "" : "#define ALPHA_TEST_OFF\n"; }
    // The texture unit of the alpha test's texture (alpha_test.glsl's layout binding); the
    // techniques use the units below it.
    static constexpr GLuint kAlphaTextureUnit = 8;
    // The triangles with welded vertices (shadow_volume_geometry.h), made on first use and shared
    // by every light.
    const WeldedScene& welded() const;

  private:
    struct MeshDraw {
        GLint first;
        GLsizei count;
    };
    // What alpha_test.glsl needs of an alpha-tested mesh: its texture (a 1x1 alpha of 1 for a
    // constant mask, so the test is factor >= cutoff), the sampler of its wrap and filter, and
    // the cutoff and factor.
    struct MeshAlpha {
        GLuint texture = 0, sampler = 0;
        float cutoff = 0.5f, factor = 1.0f;
        int tapTexels = 1;  // what one lookup reads: 4 bilinear, 1 nearest (the work counts)
    };
    void uploadVertices(const std::vector<float>& vertices);
    void uploadAlphaMasks();
    GLuint samplerFor(const AlphaMask& mask);
    // Sets `program`'s alpha-test uniforms (and binds the mask) for `mesh`.
    void setAlphaTest(GLuint program, size_t mesh) const;

    const Scene& scene_;
    LocalFrame frame_;
    Bounds3d lsBounds_;
    std::vector<MeshDraw> draws_;
    GlBuffer vbo_;
    GlVertexArray vao_;
    bool anyAlphaTested_ = false;
    std::vector<std::optional<MeshAlpha>> alpha_;  // per mesh; empty: drawn opaque
    std::vector<GlTexture> alphaTextures_;         // per Scene::alphaTextures, then the 1x1 of 1
    std::vector<GlSampler> samplers_;              // one per (wrapS, wrapT, filter) in use
    std::vector<uint32_t> samplerKeys_;
    mutable std::unique_ptr<WeldedScene> welded_;
};

}  // namespace so
