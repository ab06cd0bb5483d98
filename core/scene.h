// The scene model shared by the oracle and the raster path: parsed once, then plain immutable data.
// Everything here is in world space and in double precision; each path converts to its own
// precision and frame (the oracle recentres before going to float, see core/local_frame.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/lights/light.h"

namespace so {

struct MeshAnimation;  // core/gltf_animation.h

// Axis-aligned box in world space. Empty until a point is added.
struct Bounds3d {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()};
    glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
    bool empty() const { return !(lo.x <= hi.x); }
    void extend(const glm::dvec3& p);
    void extend(const Bounds3d& b);
    glm::dvec3 center() const { return 0.5 * (lo + hi); }
    glm::dvec3 diagonal() const { return hi - lo; }
    double extent() const;  // length of the diagonal
};

// What the scene file says about the camera; camera.h turns it into rays and matrices.
struct CameraDesc {
    glm::dvec3 wsEye{0.0};
    glm::dvec3 wsTarget{0.0, 0.0, -1.0};
    glm::dvec3 wsUp{0.0, 1.0, 0.0};
    double vfovDeg = 40.0;  // full vertical field of view
    int width = 512;
    int height = 512;
};

// A camera moving through the scene (scene_format 2, `camera_path`; docs/scene-format.md): poses
// at parameter values t, strictly increasing. camera_path.h samples it into per-frame cameras; the
// image size and, where a key leaves them out, up and vfov_deg come from the scene's camera.
struct CameraKeyframe {
    double t = 0.0;
    glm::dvec3 wsEye{0.0};
    glm::dvec3 wsTarget{0.0, 0.0, -1.0};
    std::optional<glm::dvec3> wsUp;  // absent: the scene camera's
    std::optional<double> vfovDeg;   // absent: the scene camera's
};

enum class PathInterpolation { Linear, CatmullRom };

struct CameraPath {
    std::string file;  // the scene file as named, for errors found while sampling
    // At least 2, t strictly increasing. A `poses` list is keyframes at t = 0, 1, 2, ... (linear).
    std::vector<CameraKeyframe> keyframes;
    PathInterpolation interpolation = PathInterpolation::Linear;
};

// scene_format 5: the scene as a sequence of frames on one clock (docs/scene-format.md#sequence).
// Frame i is at t = i / fps seconds; glTF animations, light_paths and (in a sequence) camera_path
// are all read on that clock. core/scene_pose.h poses the scene at a time.
struct Sequence {
    int frames = 0;         // >= 1
    double fps = 0.0;       // > 0
    std::string animation;  // the glTF animation that plays; empty: every clip
};

// A light moving on the sequence's clock (scene_format 5, `light_paths`; core/light_path.h): keys
// at t seconds, strictly increasing, each with the same fields: a position (every light but a
// directional one; an area light moves rigidly, its centre there) and/or a direction (directional
// and spot lights; unit).
struct LightKeyframe {
    double t = 0.0;
    std::optional<glm::dvec3> wsPosition;
    std::optional<glm::dvec3> wsDirection;
};

struct LightPath {
    std::string light;                     // the name of the light it moves
    std::vector<LightKeyframe> keyframes;  // at least 2
    PathInterpolation interpolation = PathInterpolation::Linear;
};

// How a texture repeats outside [0, 1] (glTF sampler wrapS / wrapT), and how it is read.
enum class TextureWrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureFilter : uint8_t { Nearest, Bilinear };

// The alpha channel of a base colour texture, decoded through OpenImageIO (core/image_codec.h):
// what an alpha test reads. Texel (0, 0) is the image's top-left, at uv (0, 0) (glTF's
// convention: no flip).
struct AlphaTexture {
    std::string name;  // "FILE#images[i]", for people
    int width = 0, height = 0;
    std::vector<float> alpha;  // width * height, row by row from the top, each in [0, 1]
    // The image file's bytes as read (PNG, JPEG or WebP), for `shadow-oracle export`
    // (core/gltf_export.h), which embeds the source image; empty for a texture made in memory.
    std::vector<unsigned char> encoded;
};

// An alpha-tested material: glTF alphaMode MASK, or BLEND read as MASK at cutoff 0.5
// (docs/scene-format.md). Where factor * texture alpha at a point is below `cutoff`, the surface
// is not there, for every ray of the oracle and every raster pass (core/alpha_mask.h).
struct AlphaMask {
    float cutoff = 0.5f;
    float factor = 1.0f;  // baseColorFactor's alpha
    int texture = -1;     // index into Scene::alphaTextures; -1: the alpha is `factor` alone
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    TextureFilter filter = TextureFilter::Nearest;
    bool fromBlend = false;  // the file said BLEND
};

// One drawn mesh primitive (a glTF primitive instanced by one node). Its index in Scene::meshes
// is its `id.mesh`; the triangle index within `indices` / 3 is its `id.prim`.
struct MeshPrimitive {
    std::string name;                     // "FILE#node/mesh/primitive", for people
    std::vector<glm::dvec3> wsPositions;  // node transforms and scene-file placement applied
    std::vector<uint32_t> indices;        // 3 per triangle, all < wsPositions.size()
    size_t degenerateTriangles = 0;       // zero-area in double; kept (ids stay stable), counted
    // Alpha-tested primitives only: the material, and the base colour texture's coordinates per
    // vertex (KHR_texture_transform applied; a constant-alpha mask has none).
    std::optional<AlphaMask> alpha;
    std::vector<glm::vec2> uvs;
    // The glTF's TEXCOORD_1 per vertex, when the primitive has it: a lightmap's coordinates
    // (raster_compare/gl/lightmaps/lightmap_atlas.h); empty otherwise. Read for every primitive,
    // checked like the other attributes (VEC2 float or normalized unsigned byte or short, finite,
    // one a vertex).
    std::vector<glm::vec2> lightmapUvs;
    // Its scene-file entry says "dynamic": true (scene_format 3): the object moves, so a lightmap
    // does not bake it (its shadows are left out). The oracle and every other technique ignore it.
    bool dynamic = false;
    // The glTF material's doubleSided (false without a material, and for meshes made in memory).
    // Nothing traced reads it: the oracle's rays meet both sides; `export` keeps it for engines.
    bool doubleSided = false;
    // In a scene with a sequence, a primitive under a node that a played glTF animation moves:
    // how it moves (core/gltf_animation.h); null for a still one. wsPositions are its pose at
    // t = 0. Shared, immutable: copies of the scene share it.
    std::shared_ptr<const MeshAnimation> animation;
    size_t triangleCount() const { return indices.size() / 3; }
};

struct SceneStats {
    size_t triangles = 0;
    size_t degenerateTriangles = 0;
    size_t skippedPrimitives = 0;  // non-triangle glTF primitives (points, lines), counted
    // glTF extensions used by a geometry file that no loader step reads, sorted, each once
    // (docs/scene-format.md, "glTF extensions").
    std::vector<std::string> gltfExtensionsIgnored;
    std::vector<std::string> warnings;
    bool totalTrianglesExceeded(const struct LoadLimits& limits) const;
};

// A glTF file of the scene as the scene file places it (docs/scene-format.md): its own node
// transforms, then `scale`, then `translate`. `shadow-oracle view` hands these to other renderers
// (docs/external.md); a bare glTF scene is one source, unscaled.
struct GeometrySource {
    std::filesystem::path file;  // absolute
    glm::dvec3 translate{0.0}, scale{1.0};
};

struct Scene {
    std::filesystem::path path;  // the file the user named
    std::string contentHash;     // hash of the scene file and every file it references
    CameraDesc camera;
    std::optional<CameraPath> cameraPath;  // scene_format 2 only; for compare --frames-path
    std::optional<Sequence> sequence;      // scene_format 5 only; core/scene_pose.h
    std::vector<LightPath> lightPaths;     // scene_format 5, with a sequence; at most one a light
    std::vector<MeshPrimitive> meshes;
    std::vector<GeometrySource> geometry;
    std::vector<Light> lights;
    std::vector<std::string> effects;  // as given, validated; default {"hard"}
    bool hasEffect(const std::string& e) const;
    std::vector<AlphaTexture> alphaTextures;  // of the alpha-tested materials
    // Whether mesh `m` is alpha-tested: it has a mask and the effects include "alpha" (without
    // it, masks are drawn opaque, with a warning).
    bool alphaTested(size_t m) const { return meshes[m].alpha && hasEffect("alpha"); }
    Bounds3d wsBounds;  // of all mesh vertices
    SceneStats stats;
};

// Limits that bound every allocation a hostile file could cause. Documented in
// docs/scene-format.md; a file beyond them is an input error, never a crash.
struct LoadLimits {
    uint64_t maxFileBytes = uint64_t(1) << 30;   // any one file read (scene, .gltf, .bin, .glb)
    uint64_t maxTotalBytes = uint64_t(4) << 30;  // all files of one scene together
    uint64_t maxTrianglesPerMesh = uint64_t(1) << 24;  // id.prim is stored exactly in float32
    uint64_t maxMeshes = uint64_t(1) << 24;            // id.mesh likewise
    uint64_t maxTotalTriangles = uint64_t(1) << 28;
    int maxImageSide = 16384;                          // alpha textures: either side
    uint64_t maxImagePixels = uint64_t(1) << 26;       // one alpha texture
    uint64_t maxTotalImagePixels = uint64_t(1) << 28;  // all alpha textures of a scene
    int maxNodeDepth = 256;
    size_t maxLights = 64;
    size_t maxPathKeyframes = 10000;                // camera_path keyframes or poses
    int maxSequenceFrames = 100000;                 // sequence.frames
    uint64_t maxAnimationKeys = uint64_t(1) << 20;  // keys of the played glTF clips, all together
};

// Loads a scene file (.json, see docs/scene-format.md) or a bare .gltf/.glb. Throws InputError
// with a one-line message naming the file and the field.
Scene loadScene(const std::filesystem::path& path, const LoadLimits& limits = {});

// A scene made in memory (the C++ package and the Python module): `description` is a scene file's
// JSON without "scene_format" and "geometry" (camera, camera_path, lights, effects: the same keys,
// checked the same way, docs/scene-format.md); the meshes are given, their positions in world
// space. Errors name `display` and the field ("meshes[2].triangles"). The content hash covers the
// description and every vertex and index.
Scene sceneFromMemory(const std::string& description, std::vector<MeshPrimitive> meshes,
                      const std::string& display = "(scene in memory)",
                      const LoadLimits& limits = {});

// The largest vertex coordinate accepted, in absolute value: 2^62 (about 4.6e18), so that a sum of
// three squared coordinates stays finite in float (docs/scene-format.md, limits). With a vertex at
// 1e30 the oracle's float frame rounded a floor of size 16 to a point (docs/hard-cases.md).
inline constexpr double kMaxCoordinate = 0x1.0p62;

// Counts degenerate triangles, fills bounds and stats. Used by the loaders and by tests that
// build scenes in code. Throws InputError (file: scene.path, field "geometry") for a vertex beyond
// kMaxCoordinate.
void finalizeScene(Scene& scene);

}  // namespace so
