// Tests of core/gltf_loader: a corpus of broken files (one per validation rule, listed with the
// error each must give in tests/data/broken_gltf/expected.tsv), small valid models with exact
// expected values, and the shared real-world assets when they are present.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/scene.h"

namespace fs = std::filesystem;

namespace {

const fs::path kData = SO_TEST_DATA_DIR;
const fs::path kBroken = kData / "broken_gltf";
const fs::path kValid = kData / "gltf";
const fs::path kShared = SO_SHARED_DIR;

so::GltfContent load(const fs::path& p, const so::LoadLimits& limits = {},
                     const glm::dmat4& wsFromFile = glm::dmat4(1.0)) {
    return so::loadGltf(p, p.filename().string(), wsFromFile, limits);
}

// Loads a file that must fail; returns the message.
std::string loadError(const fs::path& p, const so::LoadLimits& limits = {}) {
    try {
        load(p, limits);
    } catch (const so::InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << p << " loaded without an error";
    return "";
}

std::map<std::string, std::string> readExpected() {
    std::map<std::string, std::string> expected;
    std::ifstream in(kBroken / "expected.tsv");
    EXPECT_TRUE(in) << "cannot read expected.tsv";
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        size_t tab = line.find('\t');
        EXPECT_NE(tab, std::string::npos) << "bad line in expected.tsv: " << line;
        if (tab == std::string::npos) continue;
        expected[line.substr(0, tab)] = line.substr(tab + 1);
    }
    return expected;
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double eps = 1e-12) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

}  // namespace

TEST(GltfLoader, BrokenCorpusGivesOneLineErrors) {
    const auto expected = readExpected();
    ASSERT_GT(expected.size(), 20u);
    for (const auto& [file, substring] : expected) {
        SCOPED_TRACE(file);
        ASSERT_TRUE(fs::exists(kBroken / file)) << "listed but missing";
        std::string msg = loadError(kBroken / file);
        EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << msg;
        EXPECT_NE(msg.find(substring), std::string::npos)
            << "message: " << msg << "\nexpected to contain: " << substring;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\r'), std::string::npos) << msg;
    }
}

TEST(GltfLoader, BrokenCorpusIsFullyListed) {
    const auto expected = readExpected();
    // Support files: the list itself, the generator and the external buffers some cases use.
    for (const auto& entry : fs::directory_iterator(kBroken)) {
        std::string name = entry.path().filename().string();
        std::string ext = entry.path().extension().string();
        if (name == "expected.tsv" || ext == ".py" || ext == ".bin" || ext == ".png") continue;
        EXPECT_TRUE(expected.count(name)) << name << " is not listed in expected.tsv";
    }
}

TEST(GltfLoader, TwoNodesTrsWorldPositionsAndIndices) {
    so::GltfContent c = load(kValid / "two_nodes.gltf");
    ASSERT_EQ(c.meshes.size(), 2u);
    EXPECT_EQ(c.skippedPrimitives, 0u);
    EXPECT_TRUE(c.warnings.empty());
    EXPECT_FALSE(c.camera.has_value());
    EXPECT_TRUE(c.lights.empty());

    const so::MeshPrimitive& a = c.meshes[0];
    EXPECT_EQ(a.name, "two_nodes.gltf#Parent/Tri/prim0");
    ASSERT_EQ(a.wsPositions.size(), 3u);
    // Parent: translation (1, 2, 3).
    EXPECT_EQ(a.wsPositions[0], glm::dvec3(1, 2, 3));
    EXPECT_EQ(a.wsPositions[1], glm::dvec3(2, 2, 3));
    EXPECT_EQ(a.wsPositions[2], glm::dvec3(1, 3, 3));
    EXPECT_EQ(a.indices, (std::vector<uint32_t>{0, 1, 2}));

    // Child: parent * T(0, 0, -5) * Rz(90 deg) * S(2).
    const so::MeshPrimitive& b = c.meshes[1];
    EXPECT_EQ(b.name, "two_nodes.gltf#node1/Tri/prim0");
    ASSERT_EQ(b.wsPositions.size(), 3u);
    expectNear(b.wsPositions[0], {1, 2, -2});
    expectNear(b.wsPositions[1], {1, 4, -2});
    expectNear(b.wsPositions[2], {-1, 2, -2});
    EXPECT_EQ(b.indices, (std::vector<uint32_t>{0, 1, 2}));

    ASSERT_EQ(c.filesRead.size(), 2u);
    EXPECT_EQ(c.filesRead[0].filename(), "two_nodes.gltf");
    EXPECT_EQ(c.filesRead[1].filename(), "two_nodes.bin");
    EXPECT_EQ(c.bytesRead,
              fs::file_size(kValid / "two_nodes.gltf") + fs::file_size(kValid / "two_nodes.bin"));
}

// TEXCOORD_1, a lightmap's coordinates (tests/data/make_lightmap_gltf.py), is read for every
// primitive that has it: floats exactly, normalized unsigned shorts as v / 65535; a primitive
// without one has none.
TEST(GltfLoader, LightmapCoordinatesAreRead) {
    const std::vector<glm::vec2> expected = {
        {0.125f, 0.25f}, {0.5f, 0.25f}, {0.5f, 0.625f}, {0.125f, 0.625f}};
    so::GltfContent f = load(kValid / "lightmap_uv.gltf");
    ASSERT_EQ(f.meshes.size(), 1u);
    EXPECT_EQ(f.meshes[0].lightmapUvs, expected);
    EXPECT_TRUE(f.meshes[0].uvs.empty()) << "TEXCOORD_1 is not an alpha mask's";
    so::GltfContent u = load(kValid / "lightmap_uv_unorm16.gltf");
    ASSERT_EQ(u.meshes[0].lightmapUvs.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(u.meshes[0].lightmapUvs[i].x, expected[i].x, 0.5 / 65535) << i;
        EXPECT_NEAR(u.meshes[0].lightmapUvs[i].y, expected[i].y, 0.5 / 65535) << i;
    }
    EXPECT_TRUE(load(kValid / "two_nodes.gltf").meshes[0].lightmapUvs.empty());
}

TEST(GltfLoader, WsFromFileIsAppliedAfterNodeTransforms) {
    glm::dmat4 place = glm::translate(glm::dmat4(1.0), glm::dvec3(10, 0, 0)) *
                       glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
    so::GltfContent c = load(kValid / "two_nodes.gltf", {}, place);
    ASSERT_EQ(c.meshes.size(), 2u);
    expectNear(c.meshes[0].wsPositions[1], {14, 4, 6});
    expectNear(c.meshes[1].wsPositions[1], {12, 8, -4});
}

TEST(GltfLoader, StripAndFanBecomeTriangleLists) {
    so::GltfContent c = load(kValid / "strip_fan.gltf");
    ASSERT_EQ(c.meshes.size(), 4u);
    // Non-indexed strip of 6 vertices: odd triangles swap their first two vertices.
    EXPECT_EQ(c.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5}));
    // Fan with uint8 indices {4, 3, 2, 1, 0}: (e0, e[i+1], e[i+2]).
    EXPECT_EQ(c.meshes[1].indices, (std::vector<uint32_t>{4, 3, 2, 4, 2, 1, 4, 1, 0}));
    // Strip with uint32 indices {0, 1, 2, 3, 4}.
    EXPECT_EQ(c.meshes[2].indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4}));
    // Non-indexed TRIANGLES (mode omitted).
    EXPECT_EQ(c.meshes[3].indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    for (const auto& m : c.meshes) EXPECT_EQ(m.wsPositions.size(), 6u);
    EXPECT_EQ(c.meshes[3].name, "strip_fan.gltf#node0/Strips/prim3");
    // A strip of two vertices has no triangle: skipped and counted, no id given.
    EXPECT_EQ(c.skippedPrimitives, 1u);
    EXPECT_EQ(c.warnings.size(), 1u);
}

TEST(GltfLoader, LightsAndCamera) {
    so::GltfContent c = load(kValid / "lights_camera.gltf");
    EXPECT_TRUE(c.meshes.empty());

    ASSERT_TRUE(c.camera.has_value());
    const so::CameraDesc& cam = *c.camera;
    expectNear(cam.wsEye, {0, 1, 10});
    expectNear(cam.wsTarget, {0, 1, 9});
    expectNear(cam.wsUp, {0, 1, 0});
    EXPECT_NEAR(cam.vfovDeg, 0.8 * 180.0 / std::numbers::pi, 1e-12);
    EXPECT_EQ(cam.width, 768);
    EXPECT_EQ(cam.height, 512);

    ASSERT_EQ(c.lights.size(), 6u);
    const so::Light& point = c.lights[0];
    EXPECT_EQ(point.name, "Key");
    EXPECT_STREQ(so::lightTypeName(point.type), "point");
    expectNear(point.wsPosition, {1, 2, 3});  // the node's scale does not move its origin

    const so::Light& spot = c.lights[1];
    EXPECT_EQ(spot.name, "Key_2");
    EXPECT_STREQ(so::lightTypeName(spot.type), "spot");
    expectNear(spot.wsPosition, {0, 5, 0});
    expectNear(spot.wsDirection, {0, -1, 0});  // -Z rotated -90 deg about X; scale 3 ignored
    EXPECT_NEAR(spot.innerConeDeg, 0.2 * 180.0 / std::numbers::pi, 1e-12);
    EXPECT_NEAR(spot.outerConeDeg, 0.5 * 180.0 / std::numbers::pi, 1e-12);

    const so::Light& sun = c.lights[2];
    EXPECT_EQ(sun.name, "sun_light_");
    EXPECT_STREQ(so::lightTypeName(sun.type), "directional");
    expectNear(sun.wsDirection, {-1, 0, 0});  // -Z rotated 90 deg about Y

    // Light 0 used by a second node: a second light, renamed.
    EXPECT_EQ(c.lights[3].name, "Key_3");
    expectNear(c.lights[3].wsPosition, {7, 8, 9});
    // Unnamed light 3 falls back to "light3".
    EXPECT_EQ(c.lights[4].name, "light3");
    // "P" is a reserved layer name; a spot without angles gets glTF's defaults.
    const so::Light& p = c.lights[5];
    EXPECT_NE(p.name, "P");
    EXPECT_STREQ(so::lightTypeName(p.type), "spot");
    EXPECT_NEAR(p.outerConeDeg, 45.0, 1e-6);
    EXPECT_EQ(p.innerConeDeg, 0.0);

    std::set<std::string> names;
    for (const auto& l : c.lights) EXPECT_TRUE(names.insert(l.name).second) << l.name;
}

TEST(GltfLoader, OrthographicCameraIsIgnoredWithAWarning) {
    so::GltfContent c = load(kValid / "ortho_camera.gltf");
    EXPECT_FALSE(c.camera.has_value());
    ASSERT_EQ(c.warnings.size(), 1u);
    EXPECT_NE(c.warnings[0].find("orthographic"), std::string::npos) << c.warnings[0];
    EXPECT_EQ(c.meshes.size(), 1u);
}

TEST(GltfLoader, MissingImagesStillLoad) {
    so::GltfContent c = load(kValid / "missing_images.gltf");
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
    // Image files are never opened, inside the folder or not.
    ASSERT_EQ(c.filesRead.size(), 1u);
    EXPECT_EQ(c.filesRead[0].filename(), "missing_images.gltf");
}

TEST(GltfLoader, LinesAndPointsAreSkippedAndCounted) {
    so::GltfContent c = load(kValid / "lines.gltf");
    // No scenes: roots are nodes 0 and 1 (node 2 is a child of 1), depth-first.
    ASSERT_EQ(c.meshes.size(), 2u);
    EXPECT_EQ(c.meshes[0].name, "lines.gltf#node1/mesh0/prim1");
    EXPECT_EQ(c.meshes[1].name, "lines.gltf#child/mesh0/prim1");
    // Line strip of mesh 1, then lines and points of mesh 0 at two nodes.
    EXPECT_EQ(c.skippedPrimitives, 5u);
    ASSERT_EQ(c.warnings.size(), 1u);
    EXPECT_NE(c.warnings[0].find("5 point or line"), std::string::npos) << c.warnings[0];
}

TEST(GltfLoader, SharedNodeIsDrawnOncePerPathInTheDefaultScene) {
    so::GltfContent c = load(kValid / "instancing.gltf");
    ASSERT_EQ(c.meshes.size(), 2u);  // scene 1 only: node 3 (in scene 0) is not drawn
    EXPECT_EQ(c.meshes[0].name, "instancing.gltf#shared/mesh0/prim0");
    EXPECT_EQ(c.meshes[0].wsPositions[1], glm::dvec3(11, 0, 0));
    EXPECT_EQ(c.meshes[1].wsPositions[1], glm::dvec3(21, 0, 0));
}

TEST(GltfLoader, LinkLeavingTheFolderIsRejected) {
    // Made at run time: a committed link would depend on the checkout's location.
    fs::path dir = fs::temp_directory_path() / ("so_gltf_link_test_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "model");
    fs::copy_file(kValid / "two_nodes.bin", dir / "outside.bin");
    std::error_code ec;
    fs::create_symlink(dir / "outside.bin", dir / "model" / "two_nodes.bin", ec);
    if (ec) {
        fs::remove_all(dir);
        GTEST_SKIP() << "cannot create a symbolic link here: " << ec.message();
    }
    fs::copy_file(kValid / "two_nodes.gltf", dir / "model" / "two_nodes.gltf");
    std::string msg = loadError(dir / "model" / "two_nodes.gltf");
    EXPECT_NE(msg.find("buffers[0].uri: 'two_nodes.bin': resolves (through a link) outside"),
              std::string::npos)
        << msg;
    // A link that stays inside the folder is fine.
    fs::rename(dir / "outside.bin", dir / "model" / "real.bin");
    fs::remove(dir / "model" / "two_nodes.bin");
    fs::create_symlink("real.bin", dir / "model" / "two_nodes.bin");
    EXPECT_EQ(load(dir / "model" / "two_nodes.gltf").meshes.size(), 2u);
    fs::remove_all(dir);
}

TEST(GltfLoader, BinaryGlb) {
    so::GltfContent c = load(kValid / "triangle.glb");
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].name, "triangle.glb#Triangle/mesh0/prim0");
    EXPECT_EQ(c.meshes[0].wsPositions[1], glm::dvec3(1, 0, 0));
    EXPECT_EQ(c.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(c.filesRead.size(), 1u);
}

TEST(GltfLoader, BufferOverFileLimitNamesTheField) {
    so::LoadLimits limits;
    limits.maxFileBytes = fs::file_size(kValid / "two_nodes.gltf");  // the .bin is larger
    ASSERT_LT(limits.maxFileBytes, fs::file_size(kValid / "two_nodes.bin"));
    std::string msg = loadError(kValid / "two_nodes.gltf", limits);
    EXPECT_NE(msg.find("two_nodes.gltf: buffers[0].uri: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("over the limit"), std::string::npos) << msg;
}

TEST(GltfLoader, OtherLimits) {
    struct Case {
        so::LoadLimits limits;
        fs::path file;
        std::string expected;
    };
    std::vector<Case> cases(7);
    cases[0] = {{}, kValid / "two_nodes.gltf", "file is"};
    cases[0].limits.maxFileBytes = 100;  // the .gltf itself
    cases[1] = {{}, kValid / "two_nodes.gltf", "buffers[0].uri: 'two_nodes.bin': files read total"};
    cases[1].limits.maxTotalBytes = fs::file_size(kValid / "two_nodes.gltf") + 100;
    cases[2] = {{}, kValid / "strip_fan.gltf", "meshes[0].primitives[0]: 4 triangles, over"};
    cases[2].limits.maxTrianglesPerMesh = 3;
    cases[3] = {{}, kValid / "strip_fan.gltf", "meshes: more than 3 drawn primitives"};
    cases[3].limits.maxMeshes = 3;
    cases[4] = {{}, kValid / "strip_fan.gltf", "meshes: more than 8 triangles in all"};
    cases[4].limits.maxTotalTriangles = 8;
    cases[5] = {{}, kValid / "lights_camera.gltf", "KHR_lights_punctual: more than 2 lights"};
    cases[5].limits.maxLights = 2;
    cases[6] = {{}, kValid / "two_nodes.gltf", "nodes[1]: node hierarchy deeper than 1 levels"};
    cases[6].limits.maxNodeDepth = 1;
    for (const Case& c : cases) {
        std::string msg = loadError(c.file, c.limits);
        EXPECT_NE(msg.find(c.expected), std::string::npos) << msg;
    }
}

TEST(GltfLoader, LoadingTwiceGivesTheSameResult) {
    so::GltfContent a = load(kValid / "strip_fan.gltf");
    so::GltfContent b = load(kValid / "strip_fan.gltf");
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
        EXPECT_EQ(a.meshes[i].wsPositions, b.meshes[i].wsPositions);
    }
}

namespace {

// Independent count of the triangles a glTF file draws, from its JSON alone: the default scene,
// depth-first, one count per node instance, index (or vertex) count / 3 per TRIANGLES primitive.
uint64_t countTriangles(const fs::path& gltf) {
    std::ifstream in(gltf);
    nlohmann::json j = nlohmann::json::parse(in);
    uint64_t total = 0;
    std::vector<int> stack;
    for (int n : j["scenes"][j.value("scene", 0)]["nodes"]) stack.push_back(n);
    while (!stack.empty()) {
        const auto& node = j["nodes"][size_t(stack.back())];
        stack.pop_back();
        if (node.contains("mesh")) {
            for (const auto& prim : j["meshes"][node["mesh"].get<size_t>()]["primitives"]) {
                EXPECT_EQ(prim.value("mode", 4), 4);
                const auto& acc =
                    prim.contains("indices")
                        ? j["accessors"][prim["indices"].get<size_t>()]
                        : j["accessors"][prim["attributes"]["POSITION"].get<size_t>()];
                total += acc["count"].get<uint64_t>() / 3;
            }
        }
        if (node.contains("children"))
            for (int ch : node["children"]) stack.push_back(ch);
    }
    return total;
}

// The shared copy of a model may lack its texture files. If an alpha-tested material's texture is
// missing, the load must fail on exactly that (a clean error naming the image); the geometry is
// then checked on a copy whose materials are made opaque.
fs::path withoutMissingAlphaTextures(const fs::path& p) {
    std::ifstream in(p);
    nlohmann::json j = nlohmann::json::parse(in);
    bool changed = false;
    for (auto& m : j["materials"]) {
        if (m.value("alphaMode", "OPAQUE") == "OPAQUE") continue;
        const int tex = m["pbrMetallicRoughness"]["baseColorTexture"].value("index", -1);
        if (tex < 0) continue;
        const std::string uri =
            j["images"][j["textures"][tex]["source"].get<int>()].value("uri", "");
        if (uri.empty() || fs::exists(p.parent_path() / uri)) continue;
        const std::string msg = loadError(p);
        EXPECT_NE(msg.find("not found or not a regular file"), std::string::npos) << msg;
        EXPECT_NE(msg.find(uri), std::string::npos) << msg;
        m["alphaMode"] = "OPAQUE";
        changed = true;
    }
    if (!changed) return p;
    const fs::path dir = fs::temp_directory_path() / ("so_shared_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(p.parent_path()))
        if (e.path().extension() == ".bin")
            fs::copy_file(e.path(), dir / e.path().filename(),
                          fs::copy_options::overwrite_existing);
    std::ofstream(dir / p.filename()) << j.dump();
    return dir / p.filename();
}

void checkSharedAsset(const std::string& name) {
    fs::path original = kShared / "assets" / name / (name + ".gltf");
    if (!fs::exists(original))
        GTEST_SKIP() << original << " is absent (shared assets not checked out)";
    const fs::path p = withoutMissingAlphaTextures(original);
    so::GltfContent c;
    ASSERT_NO_THROW(c = load(p));
    uint64_t triangles = 0;
    for (const auto& m : c.meshes) {
        triangles += m.triangleCount();
        for (uint32_t i : m.indices) ASSERT_LT(i, m.wsPositions.size());
    }
    EXPECT_GT(triangles, 0u);
    EXPECT_EQ(triangles, countTriangles(p));
    EXPECT_EQ(c.skippedPrimitives, 0u);
    EXPECT_GE(c.filesRead.size(), 2u);  // the .gltf and its .bin, and only alpha textures
    size_t images = 0;
    for (const auto& f : c.filesRead) {
        std::string ext = f.extension().string();
        const bool image = ext == ".png" || ext == ".jpg" || ext == ".jpeg";
        images += image;
        EXPECT_TRUE(ext == ".gltf" || ext == ".bin" || image) << f;
    }
    EXPECT_EQ(images, c.alphaTextures.size());
    size_t masked = 0;
    for (const auto& m : c.meshes) masked += m.alpha.has_value();
    std::printf("[ loader ] %s: %llu triangles, %zu alpha-tested primitives, %zu alpha textures\n",
                name.c_str(), (unsigned long long)triangles, masked, c.alphaTextures.size());
    if (p != original) fs::remove_all(p.parent_path());

    // The asset as shipped (textures or not) in a scene without the alpha effect: no image read.
    const fs::path tmp =
        fs::temp_directory_path() / ("so_shared_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    for (const auto& e : fs::directory_iterator(original.parent_path()))
        if (e.path().extension() == ".gltf" || e.path().extension() == ".bin")
            fs::copy_file(e.path(), tmp / e.path().filename());
    std::ofstream(tmp / "opaque.scene.json")
        << R"({"scene_format": 1, "geometry": [{"file": ")" << original.filename().string()
        << R"("}], "lights": [{"name": "sun", "type": "directional", "direction": [0, -1, 0]}]})";
    so::Scene opaque;
    ASSERT_NO_THROW(opaque = so::loadScene(tmp / "opaque.scene.json"));
    EXPECT_EQ(opaque.stats.triangles, triangles);
    EXPECT_TRUE(opaque.alphaTextures.empty());
    fs::remove_all(tmp);
}

}  // namespace

// ---- Alpha-tested materials (tests/data/make_alpha_gltf.py) ----------------------------------

TEST(GltfLoaderAlpha, MaskWithExternalTextureAndTextureTransform) {
    so::GltfContent c = load(kValid / "alpha_mask.gltf");
    ASSERT_EQ(c.meshes.size(), 1u);
    const so::MeshPrimitive& m = c.meshes[0];
    ASSERT_TRUE(m.alpha.has_value());
    EXPECT_EQ(m.alpha->cutoff, 0.25f);
    EXPECT_EQ(m.alpha->factor, 0.5f);
    EXPECT_EQ(m.alpha->texture, 0);
    EXPECT_EQ(m.alpha->wrapS, so::TextureWrap::ClampToEdge);
    EXPECT_EQ(m.alpha->wrapT, so::TextureWrap::Repeat);
    EXPECT_EQ(m.alpha->filter, so::TextureFilter::Nearest);
    EXPECT_FALSE(m.alpha->fromBlend);
    ASSERT_EQ(c.alphaTextures.size(), 1u);
    const so::AlphaTexture& t = c.alphaTextures[0];
    EXPECT_EQ(t.name, "alpha_mask.gltf#images[0]");
    ASSERT_EQ(t.width, 4);
    ASSERT_EQ(t.height, 4);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) EXPECT_EQ(t.alpha[size_t(4 * j + i)], float(85 * i) / 255.0f);
    // KHR_texture_transform's own example (offset (0, 1), a quarter turn, scale 1/2): uv (0, 0),
    // (1, 0), (0, 1) go to (0, 1), (0, 0.5), (0.5, 1), the image's lower left quadrant turned.
    ASSERT_EQ(m.uvs.size(), 3u);
    const glm::vec2 expected[3] = {{0.0f, 1.0f}, {0.0f, 0.5f}, {0.5f, 1.0f}};
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(m.uvs[size_t(k)].x, expected[k].x, 1e-6) << k;
        EXPECT_NEAR(m.uvs[size_t(k)].y, expected[k].y, 1e-6) << k;
    }
    ASSERT_EQ(c.filesRead.size(), 2u);  // the texture is read, counted and hashed
    EXPECT_EQ(c.filesRead[1].filename(), "alpha_checker.png");
    EXPECT_EQ(c.bytesRead, fs::file_size(kValid / "alpha_mask.gltf") +
                               fs::file_size(kValid / "alpha_checker.png"));
}

TEST(GltfLoaderAlpha, GlbWithTheImageInItsBuffer) {
    so::GltfContent c = load(kValid / "alpha_embedded.glb");
    ASSERT_EQ(c.meshes.size(), 1u);
    const so::MeshPrimitive& m = c.meshes[0];
    ASSERT_TRUE(m.alpha.has_value());
    EXPECT_EQ(m.alpha->filter, so::TextureFilter::Bilinear);
    EXPECT_EQ(m.alpha->wrapS, so::TextureWrap::MirroredRepeat);
    EXPECT_EQ(m.alpha->wrapT, so::TextureWrap::ClampToEdge);
    ASSERT_EQ(c.alphaTextures.size(), 1u);
    EXPECT_EQ(c.alphaTextures[0].alpha[3], 1.0f);
    EXPECT_EQ(c.alphaTextures[0].alpha[0], 0.0f);
    EXPECT_EQ(m.uvs, (std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}}));
}

TEST(GltfLoaderAlpha, BlendIsReadAsMaskAtOneHalfWithAWarning) {
    so::GltfContent c = load(kValid / "alpha_blend_datauri.gltf");
    ASSERT_EQ(c.meshes.size(), 1u);
    const so::MeshPrimitive& m = c.meshes[0];
    ASSERT_TRUE(m.alpha.has_value());
    EXPECT_TRUE(m.alpha->fromBlend);
    EXPECT_EQ(m.alpha->cutoff, 0.5f);
    EXPECT_EQ(m.alpha->wrapS, so::TextureWrap::Repeat);
    EXPECT_EQ(m.alpha->filter, so::TextureFilter::Nearest);
    ASSERT_EQ(c.alphaTextures.size(), 1u);  // grey + alpha, 2 x 2: the diagonal opaque
    EXPECT_EQ(c.alphaTextures[0].alpha, (std::vector<float>{1, 0, 0, 1}));
    bool warned = false;
    for (const std::string& w : c.warnings) warned |= w.find("BLEND read as MASK") != w.npos;
    EXPECT_TRUE(warned);
}

TEST(GltfLoaderAlpha, TextureLimitsAreCheckedBeforeDecoding) {
    so::LoadLimits limits;
    limits.maxImagePixels = 8;
    EXPECT_NE(loadError(kValid / "alpha_mask.gltf", limits).find("more than the limit of 8 pixels"),
              std::string::npos);
    limits = {};
    limits.maxImageSide = 3;
    EXPECT_NE(loadError(kValid / "alpha_mask.gltf", limits).find("limit of 3 x 3"),
              std::string::npos);
}

// The shipped grate scene: its mask is tested, and the texture is part of the scene's hash.
TEST(GltfLoaderAlpha, ShippedGrateSceneAndItsHash) {
    const fs::path scene = fs::path(SO_SCENES_DIR) / "alpha_grate.scene.json";
    so::Scene s = so::loadScene(scene);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_FALSE(s.alphaTested(0));
    EXPECT_TRUE(s.alphaTested(1));
    ASSERT_EQ(s.alphaTextures.size(), 1u);
    const so::AlphaTexture& t = s.alphaTextures[0];
    ASSERT_EQ(t.width * t.height, 64 * 64);
    const double open = double(std::count(t.alpha.begin(), t.alpha.end(), 0.0f)) / 4096.0;
    EXPECT_EQ(open, 0.5625);  // (12 / 16)^2: scenes/make_scenes.py
    float maxU = 0, maxV = 0;
    for (const glm::vec2& uv : s.meshes[1].uvs)
        maxU = std::max(maxU, uv.x), maxV = std::max(maxV, uv.y);
    EXPECT_EQ(maxU, 3.0f);  // KHR_texture_transform scale (3, 2)
    EXPECT_EQ(maxV, 2.0f);

    const fs::path tmp =
        fs::temp_directory_path() / ("so_alpha_hash_" + std::to_string(::getpid()));
    fs::create_directories(tmp / "meshes");
    fs::copy_file(scene, tmp / scene.filename());
    for (const char* f : {"floor.gltf", "grate.gltf", "grate.png"})
        fs::copy_file(scene.parent_path() / "meshes" / f, tmp / "meshes" / f);
    const std::string before = so::loadScene(tmp / scene.filename()).contentHash;
    EXPECT_EQ(before, s.contentHash);
    fs::copy_file(kValid / "alpha_checker.png", tmp / "meshes" / "grate.png",
                  fs::copy_options::overwrite_existing);
    EXPECT_NE(so::loadScene(tmp / scene.filename()).contentHash, before);
    fs::remove_all(tmp);
}

// A scene that does not test alpha needs no texture: without its PNG the grate loads, drawn
// opaque, and a warning names the image not read; with "alpha" the missing PNG is an error naming
// it (a real asset shipped without its textures, e.g. FlightHelmet's PNGs left out).
TEST(GltfLoaderAlpha, TexturesAreReadOnlyForTheAlphaEffect) {
    const fs::path scene = fs::path(SO_SCENES_DIR) / "alpha_grate.scene.json";
    const fs::path tmp =
        fs::temp_directory_path() / ("so_alpha_unread_" + std::to_string(::getpid()));
    fs::remove_all(tmp);
    fs::create_directories(tmp / "meshes");
    for (const char* f : {"floor.gltf", "grate.gltf"})  // not grate.png
        fs::copy_file(scene.parent_path() / "meshes" / f, tmp / "meshes" / f);
    std::ifstream in(scene);
    nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_TRUE(j.contains("effects"));
    j["effects"] = {"hard"};
    std::ofstream(tmp / "opaque.scene.json") << j.dump();
    j["effects"] = {"hard", "alpha"};
    std::ofstream(tmp / "alpha.scene.json") << j.dump();

    const so::Scene opaque = so::loadScene(tmp / "opaque.scene.json");
    ASSERT_EQ(opaque.meshes.size(), 2u);
    EXPECT_FALSE(opaque.alphaTested(1));
    EXPECT_TRUE(opaque.alphaTextures.empty());
    std::string warnings;
    for (const std::string& w : opaque.stats.warnings) warnings += w + "\n";
    EXPECT_NE(warnings.find("1 image(s) of alpha-tested materials not read (effects lacks "
                            "\"alpha\"): images[0] 'grate.png'"),
              std::string::npos)
        << warnings;
    EXPECT_NE(warnings.find("1 alpha-tested primitive(s) drawn opaque"), std::string::npos)
        << warnings;
    try {
        so::loadScene(tmp / "alpha.scene.json");
        ADD_FAILURE() << "the alpha effect needs the texture";
    } catch (const so::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("images[0].uri: 'grate.png': not found"),
                  std::string::npos)
            << e.what();
    }
    fs::remove_all(tmp);
}

TEST(GltfLoader, SharedFlightHelmet) {
    checkSharedAsset("FlightHelmet");
}

TEST(GltfLoader, SharedDamagedHelmet) {
    checkSharedAsset("DamagedHelmet");
}
