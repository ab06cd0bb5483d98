#include "core/gltf_draco.h"

#include <cstring>
#include <limits>
#include <map>
#include <memory>

#include <draco/compression/decode.h>

namespace so::gltf_detail {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

// One primitive's extension object, checked.
struct DracoPrimitive {
    size_t mesh = 0, prim = 0;
    size_t bufferView = 0;
    std::map<std::string, uint32_t> attributes;  // glTF attribute name -> Draco unique id
    int mode = TINYGLTF_MODE_TRIANGLES;
    std::string field;  // "meshes[i].primitives[k].extensions.KHR_draco_mesh_compression"
};

size_t checkedIndex(const Context& ctx, const Json* v, size_t size, const std::string& field,
                    const char* what) {
    if (!v || !v->is_number_unsigned() || v->get<uint64_t>() >= size)
        fail(
            ctx, field,
            "missing, or not an index of " + std::string(what) + " (" + std::to_string(size) + ")");
    return v->get<size_t>();
}

std::vector<DracoPrimitive> dracoPrimitives(const Context& ctx, const Json& doc) {
    std::vector<DracoPrimitive> out;
    const Json* meshes = member(doc, "meshes");
    const Json* views = member(doc, "bufferViews");
    const size_t viewCount = views && views->is_array() ? views->size() : 0;
    if (!meshes || !meshes->is_array()) return out;
    for (size_t m = 0; m < meshes->size(); ++m) {
        const Json* prims = member((*meshes)[m], "primitives");
        if (!prims || !prims->is_array()) continue;  // checkPrimitivesParse reports these
        for (size_t k = 0; k < prims->size(); ++k) {
            const Json* exts = member((*prims)[k], "extensions");
            const Json* ext = exts ? member(*exts, kDraco) : nullptr;
            if (!ext) continue;
            DracoPrimitive d;
            d.mesh = m;
            d.prim = k;
            d.field = idx("meshes", m) + "." + idx("primitives", k) + ".extensions." + kDraco;
            if (!ext->is_object()) fail(ctx, d.field, "not an object");
            d.bufferView = checkedIndex(ctx, member(*ext, "bufferView"), viewCount,
                                        d.field + ".bufferView", "bufferViews");
            const Json* attrs = member(*ext, "attributes");
            if (!attrs || !attrs->is_object())
                fail(ctx, d.field + ".attributes", "missing or not an object");
            for (auto it = attrs->begin(); it != attrs->end(); ++it) {
                if (!it.value().is_number_unsigned() ||
                    it.value().get<uint64_t>() > std::numeric_limits<uint32_t>::max())
                    fail(ctx, d.field + ".attributes." + printable(it.key(), 60),
                         "not a Draco attribute id (an unsigned 32-bit integer)");
                d.attributes[it.key()] = it.value().get<uint32_t>();
            }
            if (const Json* mode = member((*prims)[k], "mode"); mode && mode->is_number_integer())
                d.mode = mode->get<int>();
            // Draco holds triangle lists and point clouds only (the extension's text).
            if (d.mode != TINYGLTF_MODE_TRIANGLES && d.mode != TINYGLTF_MODE_POINTS)
                fail(ctx, idx("meshes", m) + "." + idx("primitives", k) + ".mode",
                     std::to_string(d.mode) + ": a Draco primitive must be TRIANGLES or POINTS");
            out.push_back(std::move(d));
        }
    }
    return out;
}

// The decoded mesh's data for one primitive, as the rest of the loader reads accessors.
class DracoWriter {
  public:
    DracoWriter(const Context& ctx, tinygltf::Model& model) : ctx_(ctx), model_(model) {}
    void write(const DracoPrimitive& d, const tinygltf::Primitive& prim);

  private:
    std::unique_ptr<draco::Mesh> decode(const DracoPrimitive& d, uint64_t vertices,
                                        uint64_t indices);
    void pointAccessor(const DracoPrimitive& d, int accessor, uint32_t dracoId,
                       std::vector<unsigned char> bytes, int componentType);
    std::vector<unsigned char> attributeBytes(const DracoPrimitive& d, const draco::Mesh& mesh,
                                              const std::string& name, int accessor);
    const tinygltf::Accessor& accessor(const DracoPrimitive& d, int index, const std::string& use);

    const Context& ctx_;
    tinygltf::Model& model_;
    // Accessors already pointed at decoded data, with the stream and attribute they came from.
    std::map<int, std::pair<size_t, uint32_t>> decodedFrom_;
    uint64_t decodedBytes_ = 0;
};

const tinygltf::Accessor& DracoWriter::accessor(const DracoPrimitive& d, int index,
                                                const std::string& use) {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        fail(ctx_, idx("meshes", d.mesh) + "." + idx("primitives", d.prim) + "." + use,
             "accessor " + std::to_string(index) + " out of range (" +
                 std::to_string(model_.accessors.size()) + " accessors)");
    return model_.accessors[size_t(index)];
}

std::unique_ptr<draco::Mesh> DracoWriter::decode(const DracoPrimitive& d, uint64_t vertices,
                                                 uint64_t indices) {
    const tinygltf::BufferView& bv = model_.bufferViews[d.bufferView];
    const std::string bvField = idx("bufferViews", d.bufferView);
    if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size())
        fail(ctx_, bvField + ".buffer", "out of range");
    const std::vector<unsigned char>& data = model_.buffers[size_t(bv.buffer)].data;
    uint64_t end = 0;
    if (__builtin_add_overflow(uint64_t(bv.byteOffset), uint64_t(bv.byteLength), &end) ||
        end > data.size() || bv.byteLength == 0)
        fail(ctx_, d.field + ".bufferView",
             bvField + " is empty or outside its buffer (truncated file?)");
    // The counts the accessors declare bound what the decoded mesh may hold, before it is decoded.
    const LoadLimits& limits = ctx_.limits;
    if (indices / 3 > limits.maxTrianglesPerMesh || vertices > 3 * limits.maxTrianglesPerMesh)
        fail(ctx_, d.field,
             std::to_string(indices / 3) + " triangles and " + std::to_string(vertices) +
                 " vertices, over the limits (maxTrianglesPerMesh)");
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data.data() + bv.byteOffset), bv.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        fail(ctx_, d.field,
             "the Draco data in " + bvField +
                 " does not decode: " + printable(decoded.status().error_msg_string(), 200));
    std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (uint64_t(mesh->num_points()) != vertices)
        fail(ctx_, d.field,
             "the Draco mesh has " + std::to_string(mesh->num_points()) +
                 " vertices, the POSITION accessor " + std::to_string(vertices));
    if (3 * uint64_t(mesh->num_faces()) != indices)
        fail(ctx_, d.field,
             "the Draco mesh has " + std::to_string(mesh->num_faces()) +
                 " triangles, the indices accessor " + std::to_string(indices) + " indices");
    return mesh;
}

// POSITION and TEXCOORD_n as floats, in the order of the mesh's points.
std::vector<unsigned char> DracoWriter::attributeBytes(const DracoPrimitive& d,
                                                       const draco::Mesh& mesh,
                                                       const std::string& name, int index) {
    const std::string field = d.field + ".attributes." + name;
    const draco::PointAttribute* attr = mesh.GetAttributeByUniqueId(d.attributes.at(name));
    if (!attr)
        fail(ctx_, field,
             "the Draco mesh has no attribute with id " + std::to_string(d.attributes.at(name)));
    const int components = int(componentCount(model_.accessors[size_t(index)].type));
    const int want = name == "POSITION" ? 3 : 2;
    if (components != want || attr->num_components() != want)
        fail(ctx_, field,
             "expected " + std::to_string(want) + " components; " +
                 idx("accessors", size_t(index)) + " has " + std::to_string(components) +
                 ", the Draco attribute " + std::to_string(attr->num_components()));
    std::vector<unsigned char> bytes(size_t(mesh.num_points()) * size_t(want) * sizeof(float));
    for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
        const draco::AttributeValueIndex v = attr->mapped_index(i);
        float value[3] = {0.0f, 0.0f, 0.0f};
        if (v.value() >= attr->size() || !attr->ConvertValue<float>(v, int8_t(want), value))
            fail(ctx_, field, "point " + std::to_string(i.value()) + " has no valid value");
        std::memcpy(&bytes[size_t(i.value()) * size_t(want) * sizeof(float)], value,
                    size_t(want) * sizeof(float));
    }
    return bytes;
}

// Gives accessor `index` a new buffer and bufferView holding `bytes`, read as `componentType`.
void DracoWriter::pointAccessor(const DracoPrimitive& d, int index, uint32_t dracoId,
                                std::vector<unsigned char> bytes, int componentType) {
    const auto source = std::make_pair(d.bufferView, dracoId);
    if (auto it = decodedFrom_.find(index); it != decodedFrom_.end()) {
        if (it->second != source)
            fail(ctx_, d.field,
                 idx("accessors", size_t(index)) +
                     " is decoded from two different Draco streams or attributes");
        return;  // the same stream and attribute: the same data
    }
    decodedFrom_[index] = source;
    decodedBytes_ += bytes.size();
    if (decodedBytes_ > ctx_.limits.maxTotalBytes)
        fail(ctx_, d.field,
             "the decoded Draco data totals " + std::to_string(decodedBytes_) +
                 " bytes, over the limit of " + std::to_string(ctx_.limits.maxTotalBytes));
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes);
    tinygltf::BufferView view;
    view.buffer = int(model_.buffers.size());
    view.byteOffset = 0;
    view.byteLength = buffer.data.size();
    model_.buffers.push_back(std::move(buffer));
    model_.bufferViews.push_back(view);
    tinygltf::Accessor& a = model_.accessors[size_t(index)];
    a.bufferView = int(model_.bufferViews.size() - 1);
    a.byteOffset = 0;
    a.componentType = componentType;
    a.normalized = false;
}

void DracoWriter::write(const DracoPrimitive& d, const tinygltf::Primitive& prim) {
    const std::string primField = idx("meshes", d.mesh) + "." + idx("primitives", d.prim);
    auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end() || !d.attributes.count("POSITION"))
        fail(ctx_, d.field + ".attributes", "no POSITION");
    if (prim.indices < 0)
        fail(ctx_, primField + ".indices", "missing (a Draco triangle primitive has indices)");
    const tinygltf::Accessor& positions = accessor(d, pos->second, "attributes.POSITION");
    const tinygltf::Accessor& indices = accessor(d, prim.indices, "indices");
    if (indices.type != TINYGLTF_TYPE_SCALAR)
        fail(ctx_, primField + ".indices",
             idx("accessors", size_t(prim.indices)) + " must be SCALAR");
    const std::unique_ptr<draco::Mesh> mesh = decode(d, positions.count, indices.count);

    std::vector<unsigned char> indexBytes(size_t(mesh->num_faces()) * 3 * sizeof(uint32_t));
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
        const draco::Mesh::Face& face = mesh->face(f);
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = face[size_t(c)].value();
            std::memcpy(&indexBytes[(size_t(f.value()) * 3 + size_t(c)) * sizeof v], &v, sizeof v);
        }
    }
    pointAccessor(d, prim.indices, std::numeric_limits<uint32_t>::max(), std::move(indexBytes),
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    // Only what the loader reads is decoded: POSITION, and TEXCOORD_n (alpha-tested textures,
    // lightmaps). NORMAL, TANGENT, COLOR_n, JOINTS_n and WEIGHTS_n stay without data.
    for (const auto& [name, id] : d.attributes) {
        if (name != "POSITION" && name.rfind("TEXCOORD_", 0) != 0) continue;
        auto it = prim.attributes.find(name);
        if (it == prim.attributes.end())
            fail(ctx_, d.field + ".attributes." + printable(name, 60),
                 "not among the primitive's attributes");
        accessor(d, it->second, "attributes." + name);
        pointAccessor(d, it->second, id, attributeBytes(d, *mesh, name, it->second),
                      TINYGLTF_COMPONENT_TYPE_FLOAT);
    }
}

}  // namespace

bool prepareDracoJson(const Context& ctx, Json& doc) {
    bool changed = false;
    Json* accessors = doc.contains("accessors") ? &doc["accessors"] : nullptr;
    for (const DracoPrimitive& d : dracoPrimitives(ctx, doc)) {
        const Json& prim = doc["meshes"][d.mesh]["primitives"][d.prim];
        const Json* indices = member(prim, "indices");
        if (!indices || !indices->is_number_unsigned() || !accessors || !accessors->is_array() ||
            indices->get<uint64_t>() >= accessors->size())
            continue;  // tinygltf or the loader reports these
        Json& a = (*accessors)[indices->get<size_t>()];
        if (a.is_object() && !a.contains("bufferView")) {
            a["bufferView"] = d.bufferView;
            changed = true;
        }
    }
    return changed;
}

void decodeDraco(const Context& ctx, tinygltf::Model& model, const Json& doc) {
    DracoWriter writer(ctx, model);
    for (const DracoPrimitive& d : dracoPrimitives(ctx, doc)) {
        // tinygltf keeps every primitive that checkPrimitivesParse let through, in order.
        if (d.mesh >= model.meshes.size() || d.prim >= model.meshes[d.mesh].primitives.size())
            fail(ctx, d.field, "primitive not loaded");
        if (d.mode != TINYGLTF_MODE_TRIANGLES) continue;  // points are skipped: nothing to read
        writer.write(d, model.meshes[d.mesh].primitives[d.prim]);
    }
}

}  // namespace so::gltf_detail
