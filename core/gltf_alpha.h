// Alpha-tested materials of one glTF file (docs/scene-format.md, "Alpha-tested materials"): the
// mask of each material that asks for one (alphaMode MASK, or BLEND read as MASK at 0.5), its
// base colour texture's alpha decoded through OpenImageIO (core/image_codec.h) once per image,
// and the texture coordinates of the primitives that use it, with KHR_texture_transform applied.
// Internal to the glTF loader.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>

#include "core/gltf_detail.h"
#include "core/scene.h"

namespace so::gltf_detail {

class GltfAlpha {
  public:
    GltfAlpha(Context& ctx, const tinygltf::Model& model, const Json& doc)
        : ctx_(ctx), model_(model), doc_(doc) {}

    // Gives `out` its mask and texture coordinates if the primitive's material is alpha-tested;
    // `field` names the primitive in errors ("meshes[i].primitives[k]").
    void apply(const tinygltf::Primitive& prim, uint64_t vertexCount, const std::string& field,
               MeshPrimitive& out);
    // How many primitives got a mask, and how many of those from BLEND.
    size_t masked() const { return masked_; }
    size_t fromBlend() const { return fromBlend_; }
    // The decoded textures; AlphaMask::texture indexes this list.
    std::vector<AlphaTexture> takeTextures() { return std::move(textures_); }
    // The images masks name but that were not read (Context::readAlphaTextures off), in order.
    const std::set<size_t>& imagesNotRead() const { return imagesNotRead_; }

  private:
    struct Material {
        std::optional<AlphaMask> mask;
        int texCoord = 0;            // TEXCOORD_n the texture reads
        glm::dmat3 uvFromFile{1.0};  // KHR_texture_transform
    };
    const Material& material(int index);
    Material parseMaterial(size_t index);
    void parseTexture(size_t material, const tinygltf::TextureInfo& info, Material& m);
    glm::dmat3 textureTransform(size_t material, int& texCoord) const;
    int textureSource(size_t texture) const;
    int decodedTexture(size_t image);
    std::vector<unsigned char> imageBytes(size_t image);
    std::vector<glm::vec2> readUvs(const tinygltf::Primitive& prim, const Material& m,
                                   uint64_t vertexCount, const std::string& field);

    Context& ctx_;
    const tinygltf::Model& model_;
    const Json& doc_;
    std::map<size_t, Material> materials_;
    std::map<size_t, int> textureOfImage_;
    std::set<size_t> imagesNotRead_;
    std::vector<AlphaTexture> textures_;
    uint64_t texturePixels_ = 0;
    size_t masked_ = 0, fromBlend_ = 0;
};

// The warnings for `alpha`'s work on the file: the images of alpha-tested materials not read, and
// the BLEND materials read as MASK.
void alphaWarnings(const GltfAlpha& alpha, const tinygltf::Model& model, GltfContent& out);

}  // namespace so::gltf_detail
