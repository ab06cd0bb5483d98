// The scene on the GPU: every triangle unshared, in the local frame (core/local_frame.h), each
// vertex carrying its face normal computed in double, so gl_PrimitiveID is the triangle's index in
// its mesh. Every pass draws the scene through here.
#pragma once

#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "raster_compare/gl/gl_object.h"

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
    // Draws every mesh with `program`, setting its u_meshId uniform per mesh when asked.
    void draw(GLuint program, bool setMeshId) const;
    // Draws one mesh (the program bound by the caller).
    void drawMesh(size_t mesh) const;
    size_t meshCount() const { return draws_.size(); }
    // The triangles with welded vertices (shadow_volume_geometry.h), made on first use and shared
    // by every light.
    const WeldedScene& welded() const;

  private:
    struct MeshDraw {
        GLint first;
        GLsizei count;
    };
    const Scene& scene_;
    LocalFrame frame_;
    Bounds3d lsBounds_;
    std::vector<MeshDraw> draws_;
    GlBuffer vbo_;
    GlVertexArray vao_;
    mutable std::unique_ptr<WeldedScene> welded_;
};

}  // namespace so
