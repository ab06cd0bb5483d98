// Tests of the glTF loader's extensions for compressed and quantized files (core/gltf_draco.h,
// core/gltf_meshopt.h, KHR_mesh_quantization in core/gltf_detail.h, EXT_texture_webp through
// core/webp_decode.h) and of its extension policy (core/gltf_extensions.h). The small files are
// made here with the encoders of the same Debian packages (libdraco, libmeshoptimizer, libwebp),
// so each test knows its exact answer; SO_KEEP_GLTF_FILES=DIR keeps them in DIR (the fuzz seeds in
// tests/data/gltf/ were made so, docs/fuzzing.md). The real Draco chess board is compared with its
// uncompressed copy where the shared assets are present.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <webp/encode.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/image_codec.h"
#include "core/scene.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

const fs::path kShared = SO_SHARED_DIR;
const fs::path kScenes = SO_SCENES_DIR;

// A unit quad in z = 0, two triangles, and its texture coordinates.
const std::array<float, 12> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::array<float, 8> kQuadUv = {0, 0, 1, 0, 1, 1, 0, 1};
const std::array<uint32_t, 6> kQuadIndices = {0, 1, 2, 0, 2, 3};

// A folder for one test's files: removed at the end, or kept under $SO_KEEP_GLTF_FILES.
class Folder {
  public:
    Folder() {
        const char* keep = std::getenv("SO_KEEP_GLTF_FILES");
        const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        keep_ = keep && *keep;
        dir_ = keep_ ? fs::path(keep) / test
                     : fs::temp_directory_path() /
                           ("so_gltf_compression_" + test + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    ~Folder() {
        if (!keep_) fs::remove_all(dir_);
    }
    fs::path write(const std::string& name, const Json& j) const {
        std::ofstream(dir_ / name) << j.dump();
        return dir_ / name;
    }
    // A .glb of `j` whose buffer 0 is `bin` (the BIN chunk).
    fs::path writeGlb(const std::string& name, Json j, std::vector<unsigned char> bin) const {
        j["buffers"][0] = {{"byteLength", bin.size()}};
        std::string json = j.dump();
        while (json.size() % 4 != 0) json += ' ';
        while (bin.size() % 4 != 0) bin.push_back(0);
        std::string out = "glTF";
        auto put32 = [&out](size_t v) {
            for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xff);
        };
        put32(2);
        put32(12 + 8 + json.size() + 8 + bin.size());
        put32(json.size());
        out += "JSON" + json;
        put32(bin.size());
        out += std::string("BIN\0", 4) + std::string(bin.begin(), bin.end());
        std::ofstream(dir_ / name, std::ios::binary) << out;
        return dir_ / name;
    }
    const fs::path& dir() const { return dir_; }

  private:
    fs::path dir_;
    bool keep_ = false;
};

// Bytes of one buffer, each part aligned to 4.
struct Bytes {
    std::vector<unsigned char> data;
    size_t add(const void* p, size_t n) {
        while (data.size() % 4 != 0) data.push_back(0);
        const size_t at = data.size();
        const auto* b = static_cast<const unsigned char*>(p);
        data.insert(data.end(), b, b + n);
        return at;
    }
    std::string uri() const { return "data:application/octet-stream;base64," + so::base64(data); }
};

// One node, one mesh of one primitive; the rest is filled in by each test.
Json skeleton() {
    return {{"asset", {{"version", "2.0"}}},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", Json::object()}}}}}}},
            {"accessors", Json::array()},
            {"bufferViews", Json::array()},
            {"buffers", Json::array()}};
}

so::GltfContent load(const fs::path& p, const so::LoadLimits& limits = {}) {
    return so::loadGltf(p, p.filename().string(), glm::dmat4(1.0), limits);
}

std::string loadError(const fs::path& p, const so::LoadLimits& limits = {}) {
    try {
        load(p, limits);
    } catch (const so::InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        return what;
    }
    ADD_FAILURE() << p << " loaded without an error";
    return "";
}

// Triangles as position triples, each rotated to start at its smallest index: the meshopt index
// codec keeps the order of triangles and their winding but may rotate a triangle's corners.
std::vector<std::array<uint32_t, 3>> canonicalTriangles(const std::vector<uint32_t>& indices) {
    std::vector<std::array<uint32_t, 3>> out;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        std::array<uint32_t, 3> tri = {indices[t], indices[t + 1], indices[t + 2]};
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
        out.push_back(tri);
    }
    return out;
}

void expectQuadPositions(const so::MeshPrimitive& m, double scale = 1.0) {
    ASSERT_EQ(m.wsPositions.size(), 4u);
    for (size_t i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(m.wsPositions[i][c], scale * kQuad[3 * i + size_t(c)]) << i << " " << c;
}

}  // namespace

// ---- EXT_meshopt_compression
// ---------------------------------------------------------------------

namespace {

struct MeshoptFile {
    Json doc = skeleton();
    Bytes compressed;
};

// The quad's positions (ATTRIBUTES, optionally EXPONENTIAL-filtered) and indices (TRIANGLES) in
// buffer 0, decoded into buffer 1, a fallback buffer without data.
MeshoptFile meshoptQuad(bool expFilter) {
    MeshoptFile f;
    std::vector<unsigned char> vertexData(sizeof kQuad);
    std::memcpy(vertexData.data(), kQuad.data(), sizeof kQuad);
    if (expFilter)  // 24-bit mantissas: 0 and 1 are exact
        meshopt_encodeFilterExp(vertexData.data(), 4, 12, 24, kQuad.data());
    std::vector<unsigned char> v(meshopt_encodeVertexBufferBound(4, 12));
    v.resize(meshopt_encodeVertexBuffer(v.data(), v.size(), vertexData.data(), 4, 12));
    std::vector<unsigned char> ix(meshopt_encodeIndexBufferBound(6, 4));
    ix.resize(meshopt_encodeIndexBuffer(ix.data(), ix.size(), kQuadIndices.data(), 6));
    const size_t vAt = f.compressed.add(v.data(), v.size());
    const size_t iAt = f.compressed.add(ix.data(), ix.size());
    Json& d = f.doc;
    d["extensionsUsed"] = {"EXT_meshopt_compression"};
    d["extensionsRequired"] = {"EXT_meshopt_compression"};
    d["meshes"][0]["primitives"][0] = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}};
    d["accessors"] = {
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}};
    Json posExt = {{"buffer", 0},      {"byteOffset", vAt}, {"byteLength", v.size()},
                   {"byteStride", 12}, {"count", 4},        {"mode", "ATTRIBUTES"}};
    if (expFilter) posExt["filter"] = "EXPONENTIAL";
    d["bufferViews"] = {{{"buffer", 1},
                         {"byteOffset", 0},
                         {"byteLength", 48},
                         {"byteStride", 12},
                         {"extensions", {{"EXT_meshopt_compression", posExt}}}},
                        {{"buffer", 1},
                         {"byteOffset", 48},
                         {"byteLength", 24},
                         {"extensions",
                          {{"EXT_meshopt_compression",
                            {{"buffer", 0},
                             {"byteOffset", iAt},
                             {"byteLength", ix.size()},
                             {"byteStride", 4},
                             {"count", 6},
                             {"mode", "TRIANGLES"}}}}}}};
    d["buffers"] = {
        {{"byteLength", f.compressed.data.size()}, {"uri", f.compressed.uri()}},
        {{"byteLength", 72}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    return f;
}

void expectQuad(const so::GltfContent& c) {
    ASSERT_EQ(c.meshes.size(), 1u);
    expectQuadPositions(c.meshes[0]);
    EXPECT_EQ(canonicalTriangles(c.meshes[0].indices),
              canonicalTriangles({kQuadIndices.begin(), kQuadIndices.end()}));
}

}  // namespace

TEST(GltfCompression, MeshoptVerticesAndTrianglesIntoAFallbackBuffer) {
    Folder dir;
    const so::GltfContent c = load(dir.write("meshopt_quad.gltf", meshoptQuad(false).doc));
    expectQuad(c);
    EXPECT_TRUE(c.gltfExtensionsIgnored.empty());
}

TEST(GltfCompression, MeshoptExponentialFilter) {
    Folder dir;
    expectQuad(load(dir.write("meshopt_exp.gltf", meshoptQuad(true).doc)));
}

TEST(GltfCompression, MeshoptIndexSequenceWithQuantizedPositions) {
    // What gltfpack writes: positions as non-normalized UNSIGNED_SHORT (stride 8), scaled by the
    // node; indices as an INDICES sequence of UNSIGNED_SHORT, whose order is kept exactly.
    const std::array<uint16_t, 16> positions = {0, 0, 0, 0, 4, 0, 0, 0, 4, 4, 0, 0, 0, 4, 0, 0};
    const std::array<uint32_t, 6> indices = {0, 1, 2, 2, 3, 0};
    std::vector<unsigned char> v(meshopt_encodeVertexBufferBound(4, 8));
    v.resize(meshopt_encodeVertexBuffer(v.data(), v.size(), positions.data(), 4, 8));
    std::vector<unsigned char> ix(meshopt_encodeIndexSequenceBound(6, 4));
    ix.resize(meshopt_encodeIndexSequence(ix.data(), ix.size(), indices.data(), 6));
    Bytes b;
    const size_t vAt = b.add(v.data(), v.size()), iAt = b.add(ix.data(), ix.size());
    Json d = skeleton();
    d["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    d["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    d["nodes"][0]["scale"] = {0.25, 0.25, 0.25};
    d["meshes"][0]["primitives"][0] = {{"attributes", {{"POSITION", 0}}}, {"indices", 1}};
    d["accessors"] = {
        {{"bufferView", 0}, {"componentType", 5123}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}};
    auto ext = [](size_t at, size_t len, int stride, const char* mode) {
        return Json{{"EXT_meshopt_compression",
                     {{"buffer", 0},
                      {"byteOffset", at},
                      {"byteLength", len},
                      {"byteStride", stride},
                      {"count", mode[0] == 'A' ? 4 : 6},
                      {"mode", mode}}}};
    };
    d["bufferViews"] = {{{"buffer", 1},
                         {"byteLength", 32},
                         {"byteStride", 8},
                         {"extensions", ext(vAt, v.size(), 8, "ATTRIBUTES")}},
                        {{"buffer", 1},
                         {"byteOffset", 32},
                         {"byteLength", 12},
                         {"extensions", ext(iAt, ix.size(), 2, "INDICES")}}};
    d["buffers"] = {
        {{"byteLength", b.data.size()}, {"uri", b.uri()}},
        {{"byteLength", 44}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    Folder dir;
    const so::GltfContent c = load(dir.write("meshopt_quantized.gltf", d));
    ASSERT_EQ(c.meshes.size(), 1u);
    expectQuadPositions(c.meshes[0]);
    EXPECT_EQ(c.meshes[0].indices, std::vector<uint32_t>(indices.begin(), indices.end()));
}

TEST(GltfCompression, MeshoptErrorsNameTheBufferView) {
    Folder dir;
    const std::string field = "bufferViews[0].extensions.EXT_meshopt_compression";
    {
        MeshoptFile f = meshoptQuad(false);
        f.compressed.data[0] ^= 0xff;  // the vertex codec's header byte
        f.doc["buffers"][0]["uri"] = f.compressed.uri();
        const std::string msg = loadError(dir.write("corrupt.gltf", f.doc));
        EXPECT_NE(msg.find("corrupt.gltf: " + field + ": the compressed stream does not decode"),
                  std::string::npos)
            << msg;
    }
    {
        MeshoptFile f = meshoptQuad(false);
        auto& ext = f.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
        ext["byteLength"] = f.compressed.data.size() + 1;
        const std::string msg = loadError(dir.write("past_end.gltf", f.doc));
        EXPECT_NE(msg.find(field + ": byteOffset + byteLength exceeds buffers[0]"),
                  std::string::npos)
            << msg;
    }
    {
        MeshoptFile f = meshoptQuad(false);
        f.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["mode"] = "STRIPS";
        const std::string msg = loadError(dir.write("mode.gltf", f.doc));
        EXPECT_NE(msg.find(field + ".mode: STRIPS: not ATTRIBUTES"), std::string::npos) << msg;
    }
    {
        MeshoptFile f = meshoptQuad(false);
        f.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["buffer"] = 1;
        const std::string msg = loadError(dir.write("from_fallback.gltf", f.doc));
        EXPECT_NE(msg.find(field + ".buffer: a fallback buffer holds no data"), std::string::npos)
            << msg;
    }
    {
        MeshoptFile f = meshoptQuad(false);
        f.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 5;
        const std::string msg = loadError(dir.write("count.gltf", f.doc));
        EXPECT_NE(msg.find(field + ": count * byteStride exceeds bufferViews[0].byteLength"),
                  std::string::npos)
            << msg;
    }
    {
        MeshoptFile f = meshoptQuad(false);
        f.doc["buffers"][1]["byteLength"] = 2000;  // the .gltf itself is about 1 KB
        const std::string msg = loadError(dir.write("fallback_limit.gltf", f.doc),
                                          so::LoadLimits{.maxFileBytes = 1500});
        EXPECT_NE(msg.find("buffers[1].byteLength: 2000 bytes, over the limit of 1500"),
                  std::string::npos)
            << msg;
    }
}

// ---- KHR_mesh_quantization ---------------------------------------------------------------------

namespace {

// One triangle's positions as `componentType` (normalized or not) and TEXCOORD_1 as normalized
// SHORT; stride 8 (SHORT) or 4 (BYTE) as the extension requires.
Json quantizedTriangle(int componentType, bool normalized, const std::vector<int>& values,
                       bool declare) {
    Bytes b;
    const bool isShort = componentType == 5122 || componentType == 5123;
    const size_t stride = isShort ? 8 : 4;
    std::vector<unsigned char> pos(3 * stride, 0);
    for (size_t i = 0; i < 9; ++i) {
        const size_t at = (i / 3) * stride + (i % 3) * (isShort ? 2 : 1);
        if (isShort) {
            const int16_t v = int16_t(values[i]);
            std::memcpy(&pos[at], &v, 2);
        } else {
            pos[at] = static_cast<unsigned char>(int8_t(values[i]));
        }
    }
    const std::array<int16_t, 6> uv = {0, 0, 32767, -32768, 32767, 32767};
    const size_t posAt = b.add(pos.data(), pos.size()), uvAt = b.add(uv.data(), sizeof uv);
    Json d = skeleton();
    if (declare) d["extensionsUsed"] = {"KHR_mesh_quantization"};
    d["meshes"][0]["primitives"][0] = {{"attributes", {{"POSITION", 0}, {"TEXCOORD_1", 1}}}};
    d["accessors"] = {{{"bufferView", 0},
                       {"componentType", componentType},
                       {"normalized", normalized},
                       {"count", 3},
                       {"type", "VEC3"}},
                      {{"bufferView", 1},
                       {"componentType", 5122},
                       {"normalized", true},
                       {"count", 3},
                       {"type", "VEC2"}}};
    d["bufferViews"] = {
        {{"buffer", 0}, {"byteOffset", posAt}, {"byteLength", pos.size()}, {"byteStride", stride}},
        {{"buffer", 0}, {"byteOffset", uvAt}, {"byteLength", sizeof uv}}};
    d["buffers"] = {{{"byteLength", b.data.size()}, {"uri", b.uri()}}};
    return d;
}

}  // namespace

TEST(GltfCompression, QuantizedPositionsAndTexcoords) {
    Folder dir;
    struct Case {
        const char* name;
        int componentType;
        bool normalized;
        std::vector<int> values;
        std::vector<double> expected;  // glTF's formulas, worked by hand
    };
    const std::vector<Case> cases = {
        {"short_normalized",
         5122,
         true,
         {0, 0, 0, 32767, 0, -32767, 0, -32768, 32767},
         {0, 0, 0, 1, 0, -1, 0, -1, 1}},  // -32768 clamps to -1
        {"ushort_normalized",
         5123,
         true,
         {0, 0, 0, 65535, 0, 0, 0, 65535, 65535},
         {0, 0, 0, 1, 0, 0, 0, 1, 1}},
        {"byte", 5120, false, {0, 0, 0, 5, 0, -7, 0, -128, 127}, {0, 0, 0, 5, 0, -7, 0, -128, 127}},
        {"ubyte_normalized",
         5121,
         true,
         {0, 0, 0, 255, 0, 0, 0, 255, 255},
         {0, 0, 0, 1, 0, 0, 0, 1, 1}},
        {"byte_normalized",
         5120,
         true,
         {0, 0, 0, 127, 0, -127, 0, -128, 127},
         {0, 0, 0, 1, 0, -1, 0, -1, 1}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const so::GltfContent g =
            load(dir.write(std::string("quantized_") + c.name + ".gltf",
                           quantizedTriangle(c.componentType, c.normalized, c.values, true)));
        ASSERT_EQ(g.meshes.size(), 1u);
        const so::MeshPrimitive& m = g.meshes[0];
        ASSERT_EQ(m.wsPositions.size(), 3u);
        for (size_t i = 0; i < 9; ++i) EXPECT_EQ(m.wsPositions[i / 3][int(i % 3)], c.expected[i]);
        ASSERT_EQ(m.lightmapUvs.size(), 3u);
        EXPECT_EQ(m.lightmapUvs[1], glm::vec2(1.0f, -1.0f));
        EXPECT_EQ(m.lightmapUvs[2], glm::vec2(1.0f, 1.0f));
    }
}

TEST(GltfCompression, QuantizedPositionsNeedTheExtension) {
    Folder dir;
    const std::string msg = loadError(
        dir.write("undeclared.gltf", quantizedTriangle(5122, true, std::vector<int>(9, 0), false)));
    EXPECT_NE(msg.find("undeclared.gltf: accessors[0]: POSITION must be VEC3 FLOAT (integer "
                       "positions need KHR_mesh_quantization in extensionsUsed)"),
              std::string::npos)
        << msg;
}

// ---- KHR_draco_mesh_compression
// ------------------------------------------------------------------

namespace {

// The quad as a Draco triangle soup (sequential coding, no quantization: lossless), with its
// TEXCOORD_0 as TEXCOORD_1 too (a lightmap's coordinates).
struct DracoFile {
    Json doc = skeleton();
    Bytes bytes;
    uint32_t points = 0;
};

DracoFile dracoQuad() {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (int f = 0; f < 2; ++f) {
        const uint32_t* t = &kQuadIndices[size_t(3 * f)];
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &kQuad[3 * t[0]],
                                          &kQuad[3 * t[1]], &kQuad[3 * t[2]]);
        builder.SetAttributeValuesForFace(uv, draco::FaceIndex(f), &kQuadUv[2 * t[0]],
                                          &kQuadUv[2 * t[1]], &kQuadUv[2 * t[2]]);
    }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    draco::EncoderBuffer out;
    EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &out).ok());
    DracoFile f;
    f.points = mesh->num_points();
    f.bytes.add(out.data(), out.size());
    Json& d = f.doc;
    d["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    d["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const uint32_t posId = mesh->attribute(pos)->unique_id();
    const uint32_t uvId = mesh->attribute(uv)->unique_id();
    d["meshes"][0]["primitives"][0] = {
        {"attributes", {{"POSITION", 0}, {"TEXCOORD_1", 1}}},
        {"indices", 2},
        {"extensions",
         {{"KHR_draco_mesh_compression",
           {{"bufferView", 0}, {"attributes", {{"POSITION", posId}, {"TEXCOORD_1", uvId}}}}}}}};
    d["accessors"] = {{{"componentType", 5126}, {"count", f.points}, {"type", "VEC3"}},
                      {{"componentType", 5126}, {"count", f.points}, {"type", "VEC2"}},
                      {{"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}};
    d["bufferViews"] = {{{"buffer", 0}, {"byteLength", out.size()}}};
    d["buffers"] = {{{"byteLength", f.bytes.data.size()}, {"uri", f.bytes.uri()}}};
    return f;
}

// The triangles of a primitive as corner positions and (if any) lightmap coordinates, in order.
std::vector<std::array<float, 5>> corners(const so::MeshPrimitive& m) {
    std::vector<std::array<float, 5>> out;
    for (uint32_t i : m.indices) {
        const glm::dvec3& p = m.wsPositions[i];
        const glm::vec2 uv = m.lightmapUvs.empty() ? glm::vec2(0.0f) : m.lightmapUvs[i];
        out.push_back({float(p.x), float(p.y), float(p.z), uv.x, uv.y});
    }
    return out;
}

}  // namespace

TEST(GltfCompression, DracoQuadDecodesLosslessly) {
    Folder dir;
    const DracoFile f = dracoQuad();
    const so::GltfContent c = load(dir.write("draco_quad.gltf", f.doc));
    ASSERT_EQ(c.meshes.size(), 1u);
    std::vector<std::array<float, 5>> expected;
    for (uint32_t i : kQuadIndices)
        expected.push_back(
            {kQuad[3 * i], kQuad[3 * i + 1], kQuad[3 * i + 2], kQuadUv[2 * i], kQuadUv[2 * i + 1]});
    EXPECT_EQ(corners(c.meshes[0]), expected);
}

TEST(GltfCompression, DracoQuadInAGlb) {
    Folder dir;
    const DracoFile f = dracoQuad();
    const so::GltfContent glb = load(dir.writeGlb("draco_quad.glb", f.doc, f.bytes.data));
    const so::GltfContent gltf = load(dir.write("draco_quad.gltf", f.doc));
    ASSERT_EQ(glb.meshes.size(), 1u);
    EXPECT_EQ(corners(glb.meshes[0]), corners(gltf.meshes[0]));
}

TEST(GltfCompression, DracoErrorsNameThePrimitive) {
    Folder dir;
    const std::string field = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
    {
        DracoFile f = dracoQuad();
        for (size_t i = 8; i < f.bytes.data.size(); ++i) f.bytes.data[i] = 0xff;
        f.doc["buffers"][0]["uri"] = f.bytes.uri();
        const std::string msg = loadError(dir.write("corrupt.gltf", f.doc));
        EXPECT_NE(msg.find("corrupt.gltf: " + field +
                           ": the Draco data in bufferViews[0] does "
                           "not decode"),
                  std::string::npos)
            << msg;
    }
    {
        DracoFile f = dracoQuad();
        f.doc["bufferViews"][0]["byteLength"] = f.bytes.data.size() + 4;
        const std::string msg = loadError(dir.write("truncated.gltf", f.doc));
        EXPECT_NE(msg.find(field + ".bufferView: bufferViews[0] is empty or outside its buffer"),
                  std::string::npos)
            << msg;
    }
    {
        DracoFile f = dracoQuad();
        f.doc["accessors"][0]["count"] = f.points + 1;
        const std::string msg = loadError(dir.write("count.gltf", f.doc));
        EXPECT_NE(msg.find(field + ": the Draco mesh has " + std::to_string(f.points) +
                           " vertices, the POSITION accessor " + std::to_string(f.points + 1)),
                  std::string::npos)
            << msg;
    }
    {
        DracoFile f = dracoQuad();
        f.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]
             ["attributes"]["TEXCOORD_1"] = 77;
        const std::string msg = loadError(dir.write("id.gltf", f.doc));
        EXPECT_NE(msg.find(field + ".attributes.TEXCOORD_1: the Draco mesh has no attribute with "
                                   "id 77"),
                  std::string::npos)
            << msg;
    }
    {
        DracoFile f = dracoQuad();
        f.doc["accessors"][2]["count"] = 3u << 26;  // 2^26 triangles, over maxTrianglesPerMesh
        const std::string msg = loadError(dir.write("limit.gltf", f.doc));
        EXPECT_NE(msg.find(field + ": 67108864 triangles"), std::string::npos) << msg;
    }
}

// The shipped Draco chess board (scenes/real/, or the shared original) against its uncompressed
// copy made by glTF-Transform 4.5.1 with draco3dgltf 1.5.7 (/work/shared/notes/wave4.md). Both are
// decodings of the same quantized stream: Draco stores each position as an integer q of its
// attribute's quantization bits and rebuilds min + q * range / (2^bits - 1) in float, the same
// arithmetic in draco3dgltf (Draco 1.5.7 compiled to WebAssembly) and Debian's libdraco 1.5.5, so
// the floats must be equal, not merely close. (The board's positions are quantized to 14 bits, as
// the decoded copy's value spacing shows: 2^14 - 1 steps over each primitive's extent, so each
// lies within extent / 32766 of the model before compression; both copies share that error.)
TEST(GltfCompression, DracoChessBoardEqualsItsDecodedCopy) {
    fs::path draco = kScenes / "real/chess_board/chess-board.draco.glb";
    if (!fs::exists(draco)) draco = kShared / "assets/real/chess_board/chess-board.draco.glb";
    const fs::path decoded = kShared / "assets/real/chess_board/decoded/chess-board.gltf";
    if (!fs::exists(draco) || !fs::exists(decoded))
        GTEST_SKIP() << "the Draco chess board or its decoded copy is absent (" << draco << ", "
                     << decoded << ")";
    const so::GltfContent a = load(draco), b = load(decoded);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    size_t triangles = 0;
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        SCOPED_TRACE(a.meshes[i].name);
        ASSERT_EQ(a.meshes[i].indices.size(), b.meshes[i].indices.size());
        ASSERT_EQ(a.meshes[i].wsPositions.size(), b.meshes[i].wsPositions.size());
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
        EXPECT_EQ(a.meshes[i].wsPositions, b.meshes[i].wsPositions);
        triangles += a.meshes[i].triangleCount();
    }
    EXPECT_GT(triangles, 100000u);
    EXPECT_EQ(a.gltfExtensionsIgnored, std::vector<std::string>{"KHR_materials_clearcoat"});
}

// ---- EXT_texture_webp
// ----------------------------------------------------------------------------

namespace {

// A 4 x 2 lossless WebP whose alpha is a checker of 0 and 255.
std::vector<unsigned char> webpChecker(int w = 4, int h = 2) {
    std::vector<uint8_t> rgba(size_t(w * h * 4), 200);
    for (int i = 0; i < w * h; ++i) rgba[size_t(4 * i + 3)] = ((i % w + i / w) % 2) ? 255 : 0;
    uint8_t* out = nullptr;
    const size_t n = WebPEncodeLosslessRGBA(rgba.data(), w, h, w * 4, &out);
    std::vector<unsigned char> bytes(out, out + n);
    WebPFree(out);
    return bytes;
}

// The quad with an alpha-tested material whose texture is a WebP image in a bufferView.
Json webpQuad(const std::vector<unsigned char>& image) {
    Bytes b;
    const size_t posAt = b.add(kQuad.data(), sizeof kQuad);
    const size_t uvAt = b.add(kQuadUv.data(), sizeof kQuadUv);
    const size_t ixAt = b.add(kQuadIndices.data(), sizeof kQuadIndices);
    const size_t imAt = b.add(image.data(), image.size());
    Json d = skeleton();
    d["extensionsUsed"] = {"EXT_texture_webp"};
    d["extensionsRequired"] = {"EXT_texture_webp"};
    d["meshes"][0]["primitives"][0] = {
        {"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}};
    d["accessors"] = {
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}};
    d["bufferViews"] = {{{"buffer", 0}, {"byteOffset", posAt}, {"byteLength", sizeof kQuad}},
                        {{"buffer", 0}, {"byteOffset", uvAt}, {"byteLength", sizeof kQuadUv}},
                        {{"buffer", 0}, {"byteOffset", ixAt}, {"byteLength", sizeof kQuadIndices}},
                        {{"buffer", 0}, {"byteOffset", imAt}, {"byteLength", image.size()}}};
    d["buffers"] = {{{"byteLength", b.data.size()}, {"uri", b.uri()}}};
    d["materials"] = {
        {{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    d["textures"] = {{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}};
    d["images"] = {{{"bufferView", 3}, {"mimeType", "image/webp"}}};
    return d;
}

}  // namespace

TEST(GltfCompression, WebpAlphaTexture) {
    Folder dir;
    const so::GltfContent c = load(dir.write("webp_alpha.gltf", webpQuad(webpChecker())));
    ASSERT_EQ(c.alphaTextures.size(), 1u);
    const so::AlphaTexture& t = c.alphaTextures[0];
    ASSERT_EQ(t.width, 4);
    ASSERT_EQ(t.height, 2);
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(t.alpha[size_t(i)], ((i % 4 + i / 4) % 2) ? 1.0f : 0.0f) << i;
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].alpha->texture, 0);
}

TEST(GltfCompression, WebpErrors) {
    Folder dir;
    std::vector<unsigned char> notWebp = webpChecker();
    for (size_t i = 12; i < notWebp.size(); ++i) notWebp[i] = 0x5a;  // RIFF....WEBP, then junk
    std::string msg = loadError(dir.write("not_webp.gltf", webpQuad(notWebp)));
    EXPECT_NE(msg.find("not_webp.gltf: images[0]: cannot decode the image: not a valid WebP file"),
              std::string::npos)
        << msg;
    std::vector<unsigned char> truncated = webpChecker(64, 64);
    truncated.resize(truncated.size() / 2);
    msg = loadError(dir.write("truncated_webp.gltf", webpQuad(truncated)));
    EXPECT_NE(msg.find("truncated_webp.gltf: images[0]: cannot decode the image:"),
              std::string::npos)
        << msg;
    // Refused from the header, before any pixel is decoded.
    msg = loadError(dir.write("large_webp.gltf", webpQuad(webpChecker(64, 64))),
                    so::LoadLimits{.maxImageSide = 32});
    EXPECT_NE(msg.find("images[0]: cannot decode the image: a WebP image of 64 x 64 pixels, over "
                       "the limits"),
              std::string::npos)
        << msg;
    Json d = webpQuad(webpChecker());
    d["textures"][0]["extensions"]["EXT_texture_webp"]["source"] = 3;
    msg = loadError(dir.write("webp_source.gltf", d));
    EXPECT_NE(msg.find("textures[0].extensions.EXT_texture_webp.source: missing, or not an index "
                       "of images (1)"),
              std::string::npos)
        << msg;
}

TEST(GltfCompression, TruckTownWebpTexturesAndIgnoredExtensions) {
    const fs::path town = kShared / "assets/real/truck_town/town_model.gltf";
    if (!fs::exists(town)) GTEST_SKIP() << town << " is absent (shared assets not checked out)";
    for (const char* name : {"grass_lossy.webp", "cement_lossy.webp"}) {
        std::ifstream in(town.parent_path() / "textures" / name, std::ios::binary);
        const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), {});
        const so::TextureRgba t = so::decodeTextureRgba(bytes);
        EXPECT_GT(t.width, 0) << name;
        EXPECT_EQ(t.rgba.size(), size_t(t.width) * size_t(t.height) * 4) << name;
    }
    const so::GltfContent c = load(town);
    EXPECT_GT(c.meshes.size(), 0u);
    EXPECT_EQ(c.gltfExtensionsIgnored,
              (std::vector<std::string>{"OMI_physics_body", "OMI_physics_shape"}));
}

// ---- Extension policy
// ----------------------------------------------------------------------------

namespace {

Json triangleWithExtensions(const Json& used, const Json& required) {
    Json d = skeleton();
    Bytes b;
    const std::array<float, 9> tri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    b.add(tri.data(), sizeof tri);
    d["meshes"][0]["primitives"][0] = {{"attributes", {{"POSITION", 0}}}};
    d["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}};
    d["bufferViews"] = {{{"buffer", 0}, {"byteLength", sizeof tri}}};
    d["buffers"] = {{{"byteLength", b.data.size()}, {"uri", b.uri()}}};
    if (!used.is_null()) d["extensionsUsed"] = used;
    if (!required.is_null()) d["extensionsRequired"] = required;
    return d;
}

}  // namespace

TEST(GltfCompression, UnknownRequiredExtensionIsAnError) {
    Folder dir;
    const std::string msg =
        loadError(dir.write("foo.gltf", triangleWithExtensions({"EXT_foo"}, {"EXT_foo"})));
    EXPECT_EQ(msg, "foo.gltf: extensionsRequired: unsupported extension EXT_foo");
    for (const char* coverage : {"KHR_materials_variants", "KHR_materials_pbrSpecularGlossiness",
                                 "KHR_texture_basisu", "EXT_mesh_gpu_instancing"}) {
        const std::string m =
            loadError(dir.write("cov.gltf", triangleWithExtensions({coverage}, {coverage})));
        EXPECT_NE(m.find(std::string("unsupported extension ") + coverage), std::string::npos) << m;
    }
    EXPECT_NE(loadError(dir.write("bad.gltf", triangleWithExtensions({"a"}, "EXT_foo")))
                  .find("bad.gltf: extensionsRequired: not an array"),
              std::string::npos);
}

TEST(GltfCompression, OptionalUnknownExtensionsAreIgnoredAndListed) {
    Folder dir;
    const fs::path p = dir.write(
        "used.gltf", triangleWithExtensions({"OMI_physics_body", "KHR_materials_clearcoat",
                                             "EXT_foo", "KHR_texture_transform"},
                                            {"KHR_materials_clearcoat"}));
    const so::GltfContent c = load(p);
    EXPECT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.gltfExtensionsIgnored,
              (std::vector<std::string>{"EXT_foo", "KHR_materials_clearcoat", "OMI_physics_body"}));
    // A scene file gathers them from every geometry file, each once, sorted.
    std::ofstream(dir.dir() / "two.scene.json")
        << R"({"scene_format": 1, "geometry": [{"file": "used.gltf"}, {"file": "other.gltf"}],
              "lights": [{"name": "sun", "type": "directional", "direction": [0, -1, 0]}]})";
    dir.write("other.gltf", triangleWithExtensions({"ABC_other", "EXT_foo"}, nullptr));
    const so::Scene scene = so::loadScene(dir.dir() / "two.scene.json");
    EXPECT_EQ(scene.stats.gltfExtensionsIgnored,
              (std::vector<std::string>{"ABC_other", "EXT_foo", "KHR_materials_clearcoat",
                                        "OMI_physics_body"}));
}
