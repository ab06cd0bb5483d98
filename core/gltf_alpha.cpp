#include "core/gltf_alpha.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/image_codec.h"

namespace so::gltf_detail {

namespace {

TextureWrap wrapMode(const Context& ctx, int mode, const std::string& field) {
    switch (mode) {
        case TINYGLTF_TEXTURE_WRAP_REPEAT:
            return TextureWrap::Repeat;
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
            return TextureWrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
            return TextureWrap::MirroredRepeat;
        default:
            fail(ctx, field,
                 std::to_string(mode) +
                     " is not a wrap mode (33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT, 10497 "
                     "REPEAT)");
    }
}

// A member of nested objects, or null where any step is missing.
const Json* path(const Json& j, std::initializer_list<const char*> keys) {
    const Json* at = &j;
    for (const char* k : keys)
        if (!(at = member(*at, k))) return nullptr;
    return at;
}

}  // namespace

void GltfAlpha::apply(const tinygltf::Primitive& prim, uint64_t vertexCount,
                      const std::string& field, MeshPrimitive& out) {
    if (prim.material < 0) return;
    if (size_t(prim.material) >= model_.materials.size())
        fail(ctx_, field + ".material",
             std::to_string(prim.material) + " out of range (" +
                 std::to_string(model_.materials.size()) + " materials)");
    const Material& m = material(prim.material);
    if (!m.mask) return;
    out.alpha = m.mask;
    if (m.mask->texture >= 0) out.uvs = readUvs(prim, m, vertexCount, field);
    ++masked_;
    fromBlend_ += m.mask->fromBlend;
}

const GltfAlpha::Material& GltfAlpha::material(int index) {
    auto it = materials_.find(size_t(index));
    if (it == materials_.end())
        it = materials_.emplace(size_t(index), parseMaterial(size_t(index))).first;
    return it->second;
}

GltfAlpha::Material GltfAlpha::parseMaterial(size_t i) {
    const tinygltf::Material& mat = model_.materials[i];
    const std::string field = idx("materials", i);
    Material m;
    if (mat.alphaMode == "OPAQUE") return m;
    if (mat.alphaMode != "MASK" && mat.alphaMode != "BLEND")
        fail(ctx_, field + ".alphaMode",
             quoted(mat.alphaMode) + " is not one of OPAQUE, MASK, BLEND");
    AlphaMask mask;
    mask.fromBlend = mat.alphaMode == "BLEND";
    // BLEND has no cutoff in glTF; it is read as MASK at 0.5 (docs/scene-format.md).
    if (!mask.fromBlend) {
        if (!(mat.alphaCutoff >= 0.0)) {
            char value[32];
            std::snprintf(value, sizeof value, "%g", mat.alphaCutoff);
            fail(ctx_, field + ".alphaCutoff", std::string("must be >= 0, got ") + value);
        }
        mask.cutoff = float(mat.alphaCutoff);
    }
    const std::vector<double>& factor = mat.pbrMetallicRoughness.baseColorFactor;
    if (factor.size() != 4 || !(factor[3] >= 0.0 && factor[3] <= 1.0))
        fail(ctx_, field + ".pbrMetallicRoughness.baseColorFactor",
             "must be 4 numbers in [0, 1] (its alpha is the mask's factor)");
    mask.factor = float(factor[3]);
    m.mask = mask;
    const tinygltf::TextureInfo& info = mat.pbrMetallicRoughness.baseColorTexture;
    if (info.index >= 0) parseTexture(i, info, m);
    return m;
}

void GltfAlpha::parseTexture(size_t i, const tinygltf::TextureInfo& info, Material& m) {
    const std::string field = idx("materials", i) + ".pbrMetallicRoughness.baseColorTexture";
    if (size_t(info.index) >= model_.textures.size())
        fail(ctx_, field + ".index",
             std::to_string(info.index) + " out of range (" +
                 std::to_string(model_.textures.size()) + " textures)");
    const tinygltf::Texture& tex = model_.textures[size_t(info.index)];
    const std::string texField = idx("textures", size_t(info.index));
    const int source = textureSource(size_t(info.index));
    if (info.texCoord < 0) fail(ctx_, field + ".texCoord", "must be >= 0");
    m.texCoord = info.texCoord;
    m.uvFromFile = textureTransform(i, m.texCoord);
    AlphaMask& mask = *m.mask;
    if (tex.sampler >= 0) {
        if (size_t(tex.sampler) >= model_.samplers.size())
            fail(ctx_, texField + ".sampler",
                 std::to_string(tex.sampler) + " out of range (" +
                     std::to_string(model_.samplers.size()) + " samplers)");
        const tinygltf::Sampler& s = model_.samplers[size_t(tex.sampler)];
        const std::string sField = idx("samplers", size_t(tex.sampler));
        mask.wrapS = wrapMode(ctx_, s.wrapS, sField + ".wrapS");
        mask.wrapT = wrapMode(ctx_, s.wrapT, sField + ".wrapT");
        // The magnification filter says how the texture is meant to be read up close; without
        // one, nearest (what a shadow map's alpha test sees of an unfiltered mask).
        if (s.magFilter == TINYGLTF_TEXTURE_FILTER_LINEAR)
            mask.filter = TextureFilter::Bilinear;
        else if (s.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST && s.magFilter != -1)
            fail(ctx_, sField + ".magFilter",
                 std::to_string(s.magFilter) + " is not 9728 NEAREST or 9729 LINEAR");
    }
    if (ctx_.readAlphaTextures) {
        mask.texture = decodedTexture(size_t(source));
    } else {
        imagesNotRead_.insert(size_t(source));  // the mask is not tested: no texture needed
        mask.texture = -1;
    }
}

// The image a texture shows: EXT_texture_webp's `source` where the texture has one (the WebP
// image; `source` is then the fallback for viewers without WebP, and may be absent), else
// `source`.
int GltfAlpha::textureSource(size_t texture) const {
    const std::string texField = idx("textures", texture);
    const Json* textures = member(doc_, "textures");
    const Json* webp = textures && textures->is_array() && texture < textures->size()
                           ? path((*textures)[texture], {"extensions", "EXT_texture_webp"})
                           : nullptr;
    int source = model_.textures[texture].source;
    std::string field = texField + ".source";
    if (webp) {
        field = texField + ".extensions.EXT_texture_webp.source";
        const Json* s = member(*webp, "source");
        if (!s || !s->is_number_unsigned() || s->get<uint64_t>() >= model_.images.size())
            fail(ctx_, field,
                 "missing, or not an index of images (" + std::to_string(model_.images.size()) +
                     ")");
        source = s->get<int>();
    }
    if (source < 0)
        fail(ctx_, field,
             "missing (textures given only through other extensions, such as KHR_texture_basisu, "
             "are not supported)");
    if (size_t(source) >= model_.images.size())
        fail(ctx_, field,
             std::to_string(source) + " out of range (" + std::to_string(model_.images.size()) +
                 " images)");
    return source;
}

// KHR_texture_transform on the base colour texture: uv' = T(offset) R(rotation) S(scale) uv, the
// rotation turning the image clockwise (its ratified text: R maps (x, y) to (x cos + y sin,
// -x sin + y cos)); its texCoord overrides the textureInfo's.
glm::dmat3 GltfAlpha::textureTransform(size_t i, int& texCoord) const {
    const Json* materials = member(doc_, "materials");
    if (!materials || !materials->is_array() || i >= materials->size()) return glm::dmat3(1.0);
    const Json* t = path((*materials)[i], {"pbrMetallicRoughness", "baseColorTexture", "extensions",
                                           "KHR_texture_transform"});
    if (!t) return glm::dmat3(1.0);
    const std::string field = idx("materials", i) +
                              ".pbrMetallicRoughness.baseColorTexture.extensions."
                              "KHR_texture_transform";
    if (!t->is_object()) fail(ctx_, field, "expected an object");
    auto vec2 = [&](const char* key, glm::dvec2 fallback) {
        const Json* v = member(*t, key);
        if (!v) return fallback;
        if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number())
            fail(ctx_, field + "." + key, "expected 2 numbers");
        return glm::dvec2((*v)[0].get<double>(), (*v)[1].get<double>());
    };
    const glm::dvec2 offset = vec2("offset", {0.0, 0.0}), scale = vec2("scale", {1.0, 1.0});
    double rotation = 0.0;
    if (const Json* r = member(*t, "rotation")) {
        if (!r->is_number()) fail(ctx_, field + ".rotation", "expected a number");
        rotation = r->get<double>();
    }
    if (const Json* tc = member(*t, "texCoord")) {
        if (!tc->is_number_integer() || tc->get<int64_t>() < 0 || tc->get<int64_t>() > 255)
            fail(ctx_, field + ".texCoord", "expected an integer in [0, 255]");
        texCoord = tc->get<int>();
    }
    const double c = std::cos(rotation), s = std::sin(rotation);
    // Column-major: columns are the images of (1, 0, 0), (0, 1, 0) and (0, 0, 1).
    return glm::dmat3(glm::dvec3(c * scale.x, -s * scale.x, 0.0),
                      glm::dvec3(s * scale.y, c * scale.y, 0.0),
                      glm::dvec3(offset.x, offset.y, 1.0));
}

std::vector<glm::vec2> GltfAlpha::readUvs(const tinygltf::Primitive& prim, const Material& m,
                                          uint64_t vertexCount, const std::string& field) {
    const std::string name = "TEXCOORD_" + std::to_string(m.texCoord);
    auto it = prim.attributes.find(name);
    if (it == prim.attributes.end())
        fail(ctx_, field + ".attributes",
             "no " + name + " for the alpha-tested material " +
                 idx("materials", size_t(prim.material)));
    return readTexCoords(ctx_, model_, doc_, it->second, name, vertexCount, field, m.uvFromFile);
}

// The bytes of image `i`: from the file its uri names (inside the folder, within the limits), or
// as tinygltf handed them over (bufferView or data: URI).
std::vector<unsigned char> GltfAlpha::imageBytes(size_t i) {
    const tinygltf::Image& image = model_.images[i];
    const std::string field = idx("images", i);
    auto embedded = ctx_.embeddedImages.find(int(i));
    if (embedded != ctx_.embeddedImages.end()) return std::move(embedded->second);
    if (image.uri.empty()) fail(ctx_, field, "has neither a uri nor a bufferView");
    const std::string decoded = urlDecode(image.uri);
    if (std::string why = unsafeUriReason(decoded); !why.empty())
        fail(ctx_, field + ".uri", quoted(image.uri) + ": " + why);
    const std::string p = ctx_.folderPrefix + decoded;
    if (!allowedPath(ctx_, p))
        fail(ctx_, field + ".uri", quoted(image.uri) + ": outside the model's folder");
    std::vector<unsigned char> bytes;
    if (std::string why = readCapped(ctx_, p, bytes); !why.empty())
        fail(ctx_, field + ".uri",
             quoted(image.uri) + ": " + why +
                 " (an alpha-tested material's texture; a scene file without the \"alpha\" "
                 "effect draws it opaque and reads no image)");
    return bytes;
}

int GltfAlpha::decodedTexture(size_t image) {
    if (auto it = textureOfImage_.find(image); it != textureOfImage_.end()) return it->second;
    const std::string field = idx("images", image);
    const LoadLimits& limits = ctx_.limits;
    std::vector<unsigned char> bytes = imageBytes(image);
    TextureRgba rgba;
    try {
        rgba = decodeTextureRgba(bytes, limits.maxImageSide, limits.maxImageSide,
                                 limits.maxImagePixels);
    } catch (const InputError& e) {
        fail(ctx_, field, std::string("cannot decode the image: ") + e.message());
    }
    texturePixels_ += uint64_t(rgba.width) * uint64_t(rgba.height);
    if (texturePixels_ > limits.maxTotalImagePixels)
        fail(ctx_, field,
             "the alpha textures hold " + std::to_string(texturePixels_) +
                 " pixels in all, over the limit of " + std::to_string(limits.maxTotalImagePixels));
    AlphaTexture t;
    t.name = ctx_.displayName + "#" + field;
    t.width = rgba.width;
    t.height = rgba.height;
    t.alpha.resize(size_t(rgba.width) * size_t(rgba.height));
    for (size_t k = 0; k < t.alpha.size(); ++k) t.alpha[k] = rgba.rgba[4 * k + 3];
    t.encoded = std::move(bytes);
    textures_.push_back(std::move(t));
    return textureOfImage_[image] = int(textures_.size() - 1);
}

void alphaWarnings(const GltfAlpha& alpha, const tinygltf::Model& model, GltfContent& out) {
    if (!alpha.imagesNotRead().empty()) {
        std::string names;
        size_t listed = 0;
        for (size_t i : alpha.imagesNotRead()) {
            if (listed++ == 4) {
                names += ", and " + std::to_string(alpha.imagesNotRead().size() - 4) + " more";
                break;
            }
            const std::string& uri = model.images[i].uri;
            names += (names.empty() ? "" : ", ") + idx("images", i) +
                     (uri.empty() ? "" : " " + quoted(printable(uri, 60)));
        }
        out.warnings.push_back(std::to_string(alpha.imagesNotRead().size()) +
                               " image(s) of alpha-tested materials not read (effects lacks "
                               "\"alpha\"): " +
                               names);
    }
    if (alpha.fromBlend() > 0)
        out.warnings.push_back(std::to_string(alpha.fromBlend()) +
                               " primitive(s) with alphaMode BLEND read as MASK at cutoff 0.5");
}

}  // namespace so::gltf_detail
