#include "core/gltf_export.h"

#include "core/lights/light_kind.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>
#include "core/gltf_detail.h"

#include "core/camera.h"
#include "core/error.h"
#include "core/tool_info.h"

namespace so {

namespace {

using nlohmann::json;

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;

// tinygltf keeps extras and extensions as its own Value; the export builds them as JSON.
tinygltf::Value toValue(const json& j) {
    if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
    if (j.is_number_integer() && j.get<int64_t>() >= INT32_MIN && j.get<int64_t>() <= INT32_MAX)
        return tinygltf::Value(int(j.get<int64_t>()));
    if (j.is_number()) return tinygltf::Value(j.get<double>());
    if (j.is_string()) return tinygltf::Value(j.get<std::string>());
    if (j.is_array()) {
        tinygltf::Value::Array a;
        for (const json& e : j) a.push_back(toValue(e));
        return tinygltf::Value(std::move(a));
    }
    if (j.is_object()) {
        tinygltf::Value::Object o;
        for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = toValue(it.value());
        return tinygltf::Value(std::move(o));
    }
    return tinygltf::Value();
}

// World-space bounds of every vertex as the scene holds them (in double), null without geometry:
// what an engine fits a directional light's shadow camera to.
json boundsJson(const Bounds3d& b) {
    if (b.empty()) return nullptr;
    return {{"min", jsonVec3(b.lo)}, {"max", jsonVec3(b.hi)}};
}

// The rotation (x, y, z, w) whose -Z is `wsDir` (unit), with +Y as close to world up as it can
// be: a glTF camera and light look down their node's -Z.
std::vector<double> rotationLookingAlong(const glm::dvec3& wsDir, const glm::dvec3& wsUpHint) {
    const glm::dvec3 z = -wsDir;
    glm::dvec3 up = wsUpHint;
    if (glm::length(glm::cross(up, z)) < 1e-6)
        up = std::abs(z.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 x = glm::normalize(glm::cross(up, z));
    const glm::dvec3 y = glm::cross(z, x);
    const glm::dquat q = glm::quat_cast(glm::dmat3(x, y, z));
    return {q.x, q.y, q.z, q.w};
}

// Material of one exported primitive: what an engine needs to cover the same surface. The key
// orders materials so each distinct one is written once, in order of first use.
struct MaterialKey {
    bool masked = false, doubleSided = false;
    float cutoff = 0.5f, factor = 1.0f;
    int texture = -1;
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    TextureFilter filter = TextureFilter::Nearest;
    auto tie() const {
        return std::tie(masked, doubleSided, cutoff, factor, texture, wrapS, wrapT, filter);
    }
    bool operator<(const MaterialKey& o) const { return tie() < o.tie(); }
};

int glWrap(TextureWrap w) {
    switch (w) {
        case TextureWrap::ClampToEdge:
            return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        case TextureWrap::MirroredRepeat:
            return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
        case TextureWrap::Repeat:
            break;
    }
    return TINYGLTF_TEXTURE_WRAP_REPEAT;
}

// The image's type from its first bytes; empty if it is none that glTF (with EXT_texture_webp)
// can carry.
std::string mimeType(const std::vector<unsigned char>& b) {
    if (b.size() >= 8 && std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return "image/png";
    if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "image/jpeg";
    if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 &&
        std::memcmp(b.data() + 8, "WEBP", 4) == 0)
        return "image/webp";
    return "";
}

class GlbBuilder {
  public:
    GlbBuilder(const Scene& scene, const GlbExportOptions& opts) : scene_(scene), opts_(opts) {
        model_.buffers.resize(1);
        model_.scenes.resize(1);
        model_.defaultScene = 0;
    }
    std::vector<unsigned char> build();

  private:
    int addBufferView(const void* data, size_t bytes, int target);
    int addFloatAccessor(const std::vector<float>& values, int type, bool withBounds);
    void addMesh(size_t m);
    int material(size_t m);
    int texture(const MaterialKey& k);
    int image(int sceneTexture);
    int sampler(const MaterialKey& k);
    void addCamera();
    void addLight(const Light& l);
    json lightExtras(const Light& l) const;
    int addNode(tinygltf::Node node);
    void setAsset();

    const Scene& scene_;
    const GlbExportOptions& opts_;
    tinygltf::Model model_;
    std::map<MaterialKey, int> materials_;
    std::map<std::pair<int, int>, int> textures_;  // (image, sampler) -> glTF texture
    std::map<int, int> images_;                    // scene texture -> glTF image
    std::map<std::tuple<int, int, int>, int> samplers_;
    bool webp_ = false;
};

int GlbBuilder::addBufferView(const void* data, size_t bytes, int target) {
    std::vector<unsigned char>& buf = model_.buffers[0].data;
    const size_t offset = buf.size();
    // glTF: a buffer is at most 2^32 - 1 bytes in a glb (its chunk length is 32-bit).
    if (uint64_t(offset) + bytes + 3 > uint64_t(UINT32_MAX) - 64)
        throwInputError(opts_.sourcePath, "geometry",
                        "too large for one glb (over 4 GiB of vertex and image data)");
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    buf.resize((buf.size() + 3) / 4 * 4, 0);  // every view starts 4-byte aligned
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = offset;
    v.byteLength = bytes;
    v.target = target;
    model_.bufferViews.push_back(v);
    return int(model_.bufferViews.size() - 1);
}

int GlbBuilder::addFloatAccessor(const std::vector<float>& values, int type, bool withBounds) {
    const int n = tinygltf::GetNumComponentsInType(uint32_t(type));
    tinygltf::Accessor a;
    a.bufferView =
        addBufferView(values.data(), values.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = kFloat;
    a.type = type;
    a.count = values.size() / size_t(n);
    if (withBounds && a.count > 0) {  // glTF requires them on POSITION
        a.minValues.assign(size_t(n), std::numeric_limits<double>::infinity());
        a.maxValues.assign(size_t(n), -std::numeric_limits<double>::infinity());
        for (size_t i = 0; i < values.size(); ++i) {
            a.minValues[i % size_t(n)] = std::min(a.minValues[i % size_t(n)], double(values[i]));
            a.maxValues[i % size_t(n)] = std::max(a.maxValues[i % size_t(n)], double(values[i]));
        }
    }
    model_.accessors.push_back(a);
    return int(model_.accessors.size() - 1);
}

// One glTF mesh and node per scene primitive, in the scene's order, so that the exported file
// loads back with the same id.mesh and id.prim. Vertices are unshared, three per triangle, each
// with the triangle's own (flat, geometric) normal: the normal the oracle uses.
void GlbBuilder::addMesh(size_t m) {
    const MeshPrimitive& mesh = scene_.meshes[m];
    const bool uvs = scene_.alphaTested(m) && mesh.alpha->texture >= 0;
    const size_t triangles = mesh.triangleCount();
    std::vector<float> positions, normals, texcoords;
    positions.reserve(9 * triangles);
    normals.reserve(9 * triangles);
    if (uvs) texcoords.reserve(6 * triangles);
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* v = &mesh.indices[3 * t];
        const glm::dvec3 &a = mesh.wsPositions[v[0]], &b = mesh.wsPositions[v[1]],
                         &c = mesh.wsPositions[v[2]];
        glm::dvec3 n = glm::cross(b - a, c - a);
        const double len = glm::length(n);
        n = len > 0.0 ? n / len : glm::dvec3(0.0, 0.0, 1.0);  // a degenerate triangle: any
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& p = mesh.wsPositions[v[k]];
            positions.insert(positions.end(), {float(p.x), float(p.y), float(p.z)});
            normals.insert(normals.end(), {float(n.x), float(n.y), float(n.z)});
            if (uvs) texcoords.insert(texcoords.end(), {mesh.uvs[v[k]].x, mesh.uvs[v[k]].y});
        }
    }
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = addFloatAccessor(positions, TINYGLTF_TYPE_VEC3, true);
    prim.attributes["NORMAL"] = addFloatAccessor(normals, TINYGLTF_TYPE_VEC3, false);
    if (uvs) prim.attributes["TEXCOORD_0"] = addFloatAccessor(texcoords, TINYGLTF_TYPE_VEC2, false);
    prim.material = material(m);
    tinygltf::Mesh out;
    out.name = mesh.name;
    out.primitives.push_back(prim);
    if (mesh.dynamic) out.extras = toValue({{"shadow_oracle", {{"dynamic", true}}}});
    model_.meshes.push_back(out);
    tinygltf::Node node;
    node.name = mesh.name;
    node.mesh = int(model_.meshes.size() - 1);
    addNode(node);
}

int GlbBuilder::material(size_t m) {
    const MeshPrimitive& mesh = scene_.meshes[m];
    MaterialKey k;
    k.doubleSided = mesh.doubleSided;
    if (scene_.alphaTested(m)) {  // without the "alpha" effect the oracle draws it opaque
        const AlphaMask& a = *mesh.alpha;
        k.masked = true;
        k.cutoff = a.cutoff;
        k.factor = a.factor;
        k.texture = a.texture;
        if (a.texture >= 0) k.wrapS = a.wrapS, k.wrapT = a.wrapT, k.filter = a.filter;
    }
    if (auto it = materials_.find(k); it != materials_.end()) return it->second;
    tinygltf::Material mat;
    mat.name = k.masked ? "alpha_tested_" + std::to_string(materials_.size())
                        : (k.doubleSided ? "white_double_sided" : "white");
    mat.doubleSided = k.doubleSided;
    mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, k.masked ? double(k.factor) : 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 1.0;
    if (k.masked) {
        mat.alphaMode = "MASK";
        mat.alphaCutoff = double(k.cutoff);
        if (k.texture >= 0) mat.pbrMetallicRoughness.baseColorTexture.index = texture(k);
    }
    model_.materials.push_back(mat);
    return materials_[k] = int(model_.materials.size() - 1);
}

// A glTF texture is an image read through a sampler; each pair is written once.
int GlbBuilder::texture(const MaterialKey& k) {
    const std::pair<int, int> key(image(k.texture), sampler(k));
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    tinygltf::Texture t;
    t.sampler = key.second;
    if (model_.images[size_t(key.first)].mimeType == "image/webp") {
        // Core glTF knows PNG and JPEG only; the loader reads WebP through EXT_texture_webp.
        t.extensions["EXT_texture_webp"] = toValue({{"source", key.first}});
        webp_ = true;
    } else {
        t.source = key.first;
    }
    model_.textures.push_back(t);
    return textures_[key] = int(model_.textures.size() - 1);
}

// The alpha texture's source image, embedded as the bytes the scene read (never re-encoded: an
// engine decodes the same pixels the oracle did).
int GlbBuilder::image(int sceneTexture) {
    if (auto it = images_.find(sceneTexture); it != images_.end()) return it->second;
    const AlphaTexture& src = scene_.alphaTextures[size_t(sceneTexture)];
    const std::string mime = mimeType(src.encoded);
    if (mime.empty())
        throwInputError(opts_.sourcePath, printable(src.name),
                        src.encoded.empty()
                            ? "has no source image bytes to embed (a texture made in memory)"
                            : "is not a PNG, JPEG or WebP image");
    tinygltf::Image img;
    img.name = src.name;
    img.mimeType = mime;
    img.bufferView = addBufferView(src.encoded.data(), src.encoded.size(), 0);
    model_.images.push_back(img);
    return images_[sceneTexture] = int(model_.images.size() - 1);
}

// The mask's wrap modes; its filter as both magFilter and minFilter without mipmaps, since the
// oracle reads the texture at full resolution everywhere (docs/scene-format.md).
int GlbBuilder::sampler(const MaterialKey& k) {
    const int filter = k.filter == TextureFilter::Bilinear ? TINYGLTF_TEXTURE_FILTER_LINEAR
                                                           : TINYGLTF_TEXTURE_FILTER_NEAREST;
    const std::tuple<int, int, int> key(glWrap(k.wrapS), glWrap(k.wrapT), filter);
    if (auto it = samplers_.find(key); it != samplers_.end()) return it->second;
    tinygltf::Sampler s;
    s.wrapS = std::get<0>(key);
    s.wrapT = std::get<1>(key);
    s.magFilter = s.minFilter = filter;
    model_.samplers.push_back(s);
    return samplers_[key] = int(model_.samplers.size() - 1);
}

int GlbBuilder::addNode(tinygltf::Node node) {
    model_.nodes.push_back(std::move(node));
    const int i = int(model_.nodes.size() - 1);
    model_.scenes[0].nodes.push_back(i);
    return i;
}

// The view's camera: yfov and aspect exactly the view's at its width x height, znear and zfar as
// view.json has them. The node sits at the eye, its -Z at the target, its +Y the camera's up.
void GlbBuilder::addCamera() {
    const Camera cam(opts_.camera);
    tinygltf::Camera c;
    c.name = "camera";
    c.type = "perspective";
    c.perspective.yfov = opts_.camera.vfovDeg * glm::pi<double>() / 180.0;
    c.perspective.aspectRatio = double(opts_.camera.width) / double(opts_.camera.height);
    c.perspective.znear = opts_.zNear;
    c.perspective.zfar = opts_.zFar;
    model_.cameras.push_back(c);
    tinygltf::Node node;
    node.name = "camera";
    node.camera = 0;
    node.translation = {cam.wsEye().x, cam.wsEye().y, cam.wsEye().z};
    node.rotation = rotationLookingAlong(cam.wsForward(), cam.wsUp());
    addNode(node);
}

// A light on its own node named as the scene names it. Punctual lights are themselves; a rect or
// disk becomes a spot at its centre along its emitting normal, a sphere a point at its centre,
// with the true shape in the light's extras (docs/export.md).
void GlbBuilder::addLight(const Light& l) {
    tinygltf::Light out;
    out.name = l.name;
    out.color = {1.0, 1.0, 1.0};  // the scene gives no colour or power: visibility is a ratio
    out.intensity = 1.0;
    out.extras = toValue(lightExtras(l));
    tinygltf::Node node;
    node.name = l.name;
    const GltfStandIn standIn = lightKind(l.type).gltfStandIn(l, scene_.wsBounds);
    out.type = standIn.type;
    if (out.type == "spot") {
        out.spot.outerConeAngle = standIn.outerConeRad;
        out.spot.innerConeAngle = standIn.innerConeRad;
    }
    const glm::dvec3 wsAt = standIn.wsAt, wsAlong = standIn.wsAlong;
    model_.lights.push_back(out);
    node.translation = {wsAt.x, wsAt.y, wsAt.z};
    if (wsAlong != glm::dvec3(0.0))
        node.rotation = rotationLookingAlong(wsAlong, glm::dvec3(0.0, 1.0, 0.0));
    node.extensions["KHR_lights_punctual"] = toValue({{"light", int(model_.lights.size() - 1)}});
    addNode(node);
}

// extras.shadow_oracle of a light: its scene type and, for what glTF cannot say, the exact values
// (a spot's cone in degrees as the scene gives it; an area light's shape and size).
json GlbBuilder::lightExtras(const Light& l) const {
    json j = {{"type", lightTypeName(l.type)}};
    const LightKind& kind = lightKind(l.type);
    kind.gltfExtras(l, j);
    if (kind.isArea()) {
        j["size"] = kind.equalAreaDiameter(l);
        j["stand_in"] = kind.gltfStandIn(l, scene_.wsBounds).type;
    }
    return {{"shadow_oracle", j}};
}

void GlbBuilder::setAsset() {
    model_.asset.version = "2.0";
    model_.asset.generator = "shadow-oracle " + toolVersionString();
    model_.asset.extras = toValue({{"shadow_oracle",
                                    {{"tool", toolJson()},
                                     {"format_version", kGlbExportFormat},
                                     {"source_scene", opts_.sourcePath},
                                     {"scene_hash", scene_.contentHash},
                                     {"effects", scene_.effects},
                                     {"bounds", boundsJson(scene_.wsBounds)}}}});
}

std::vector<unsigned char> GlbBuilder::build() {
    setAsset();
    for (size_t m = 0; m < scene_.meshes.size(); ++m) addMesh(m);
    addCamera();
    for (const Light& l : scene_.lights) addLight(l);
    model_.extensionsUsed.push_back("KHR_lights_punctual");
    if (webp_) {
        model_.extensionsUsed.push_back("EXT_texture_webp");
        model_.extensionsRequired.push_back("EXT_texture_webp");
    }
    model_.buffers[0].name = "";
    std::ostringstream os;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model_, os, false, true))
        throwInputError(opts_.sourcePath, "", "tinygltf could not write the glb");
    const std::string bytes = os.str();
    return std::vector<unsigned char>(bytes.begin(), bytes.end());
}

}  // namespace

std::vector<unsigned char> sceneToGlb(const Scene& scene, const GlbExportOptions& opts) {
    return GlbBuilder(scene, opts).build();
}

}  // namespace so
