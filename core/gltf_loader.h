// Safe loading of glTF 2.0 (.gltf / .glb) through tinygltf 2.7: no URI may leave the folder of
// the file, every accessor is checked against its buffer, and sizes are capped: tinygltf leaves
// each of these unchecked (the cases are in tests/data/broken_gltf/). Images are decoded only for
// alpha-tested materials, through OpenImageIO, within the limits (gltf_alpha.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/scene.h"

namespace so {

struct GltfContent {
    std::vector<MeshPrimitive> meshes;  // in drawn order (docs/scene-format.md, "Mesh numbering")
    std::optional<CameraDesc> camera;   // first camera node in traversal order, if any
    std::vector<Light> lights;          // KHR_lights_punctual, named and made unique
    std::vector<AlphaTexture> alphaTextures;  // AlphaMask::texture indexes this list
    size_t skippedPrimitives = 0;
    // Extensions the file uses that the loader does not read (docs/scene-format.md, "glTF
    // extensions"), sorted.
    std::vector<std::string> gltfExtensionsIgnored;
    std::vector<std::string> warnings;
    // The file's animation names ("animations[i]" when unnamed), and whether the clip that the
    // sequence names is among them; read only for a scene with a sequence.
    std::vector<std::string> animationNames;
    bool animationClipFound = false;
    std::vector<std::filesystem::path> filesRead;  // for the content hash
    uint64_t bytesRead = 0;
};

// Loads the default scene of a glTF file, applying `wsFromFile` (the scene file's placement) after
// the node transforms. `displayName` is the name used in error messages. Without
// `readAlphaTextures` (a scene without the "alpha" effect) alpha-tested materials keep their mask
// but no texture: their images are neither read nor decoded, and a warning names them. With a
// `sequence` the file's animations play (its clip, or every clip): the moving primitives get a
// MeshAnimation and are posed at t = 0; without one, the file loads in its nodes' own TRS.
GltfContent loadGltf(const std::filesystem::path& path, const std::string& displayName,
                     const glm::dmat4& wsFromFile, const LoadLimits& limits,
                     bool readAlphaTextures = true, const Sequence* sequence = nullptr);

}  // namespace so
