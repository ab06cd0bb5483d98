// The scene-file loader: every validation rule of docs/scene-format.md gives its one-line error,
// and valid files load to exactly what they say.
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/scene.h"

namespace so {
namespace {

namespace fs = std::filesystem;
const fs::path kData = SO_TEST_DATA_DIR;

std::map<std::string, std::string> readExpected(const fs::path& tsv) {
    std::map<std::string, std::string> out;
    std::ifstream in(tsv);
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        auto tab = line.find('\t');
        if (tab == std::string::npos) continue;
        out[line.substr(0, tab)] = line.substr(tab + 1);
    }
    return out;
}

TEST(SceneLoader, BrokenCorpusGivesOneLineErrorNamingFileAndField) {
    const fs::path dir = kData / "broken_scene";
    auto expected = readExpected(dir / "expected.tsv");
    ASSERT_GT(expected.size(), 30u);
    // Every scene file in the corpus must have an expectation, so none is silently skipped.
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".json") {
            EXPECT_TRUE(expected.count(entry.path().filename().string()))
                << entry.path() << " is not in expected.tsv";
        }
    }
    for (const auto& [file, substring] : expected) {
        const fs::path path = dir / file;
        try {
            loadScene(path);
            ADD_FAILURE() << file << ": loaded without error";
        } catch (const InputError& e) {
            std::string msg = e.what();
            EXPECT_NE(msg.find(substring), std::string::npos) << file << ": got \"" << msg << "\"";
            EXPECT_EQ(msg.find('\n'), std::string::npos) << file << ": more than one line";
            // The file named is the scene file, or for mesh errors the glTF file it references.
            EXPECT_TRUE(msg.rfind(path.string() + ": ", 0) == 0 ||
                        msg.find(".gltf: ") != std::string::npos)
                << file << ": \"" << msg << "\" does not start with the file name";
        }
    }
}

TEST(SceneLoader, ValidSceneLoadsExactly) {
    Scene s = loadScene(kData / "valid" / "scene.json");
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(s.meshes[0].wsPositions[1], glm::dvec3(1, 0, 0));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].name, "key");
    EXPECT_STREQ(lightTypeName(s.lights[0].type), "point");
    EXPECT_EQ(s.lights[0].wsPosition, glm::dvec3(0, 4, 0));
    EXPECT_STREQ(lightTypeName(s.lights[1].type), "directional");
    EXPECT_NEAR(glm::length(s.lights[1].wsDirection), 1.0, 1e-15);  // normalised
    EXPECT_EQ(s.camera.width, 64);
    EXPECT_EQ(s.effects, std::vector<std::string>{"hard"});
    EXPECT_EQ(s.stats.triangles, 1u);
    EXPECT_EQ(s.contentHash.size(), 32u);
}

// Placement: translate and (non-uniform) scale apply after the file's own node transforms.
TEST(SceneLoader, TranslateAndScaleApply) {
    const fs::path dir = fs::temp_directory_path() / "so_scene_loader_test";
    fs::create_directories(dir);
    fs::copy_file(kData / "valid" / "tri.gltf", dir / "tri.gltf",
                  fs::copy_options::overwrite_existing);
    std::ofstream(dir / "s.json") << R"({"scene_format": 1,
        "geometry": [{"file": "tri.gltf", "translate": [10, 20, 30], "scale": [2, 3, 4]},
                     {"file": "tri.gltf", "scale": 0.5}],
        "lights": [{"name": "k", "type": "point", "position": [0, 1, 0]}]})";
    Scene s = loadScene(dir / "s.json");
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].wsPositions[1], glm::dvec3(12, 20, 30));
    EXPECT_EQ(s.meshes[0].wsPositions[2], glm::dvec3(10, 20, 26));
    EXPECT_EQ(s.meshes[1].wsPositions[1], glm::dvec3(0.5, 0, 0));
    // No camera given: the default framing, and a warning says so.
    EXPECT_FALSE(s.stats.warnings.empty());
}

// geometry[i].dynamic (scene_format 3) marks that entry's meshes, and only those; absent or false
// is static. Nothing else about the scene changes with it.
TEST(SceneLoader, DynamicMarksTheEntrysMeshes) {
    Scene s = loadScene(kData / "valid" / "dynamic.json");
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_FALSE(s.meshes[0].dynamic);
    EXPECT_TRUE(s.meshes[1].dynamic);
    EXPECT_FALSE(s.meshes[2].dynamic);
    EXPECT_EQ(s.meshes[1].wsPositions[1], glm::dvec3(1, 1, 0));
    // The meshes' content is what it is without the flag.
    Scene plain = loadScene(kData / "valid" / "scene.json");
    EXPECT_EQ(s.meshes[0].wsPositions, plain.meshes[0].wsPositions);
    EXPECT_EQ(s.meshes[0].indices, plain.meshes[0].indices);
}

// Effects that the lights cannot show, and area lights left cheap, are reported, not silent.
TEST(SceneLoader, EffectsWarnings) {
    const fs::path dir = fs::temp_directory_path() / "so_scene_effects_test";
    fs::create_directories(dir);
    fs::copy_file(kData / "valid" / "tri.gltf", dir / "tri.gltf",
                  fs::copy_options::overwrite_existing);
    auto warnings = [&](const std::string& lights, const std::string& effects) {
        std::ofstream(dir / "s.json")
            << R"({"scene_format": 1, "geometry": [{"file": "tri.gltf"}], "lights": [)" << lights
            << "]" << (effects.empty() ? "" : R"(, "effects": )" + effects) << "}";
        Scene s = loadScene(dir / "s.json");
        std::string all;
        for (const std::string& w : s.stats.warnings) all += w + "\n";
        return all;
    };
    const std::string point = R"({"name": "k", "type": "point", "position": [0, 3, 0]})";
    const std::string rect =
        R"({"name": "panel", "type": "rect", "center": [0, 3, 0], "u": [1, 0, 0], "v": [0, 0, 1]})";
    EXPECT_NE(warnings(point, R"(["penumbra"])").find("no area light"), std::string::npos);
    EXPECT_NE(warnings(rect, R"(["hard"])").find("traced as a point light at its centre"),
              std::string::npos);
    EXPECT_EQ(warnings(rect, R"(["penumbra", "contact"])").find("penumbra"), std::string::npos);
    Scene s = loadScene(dir / "s.json");
    EXPECT_TRUE(s.hasEffect("contact"));
    EXPECT_STREQ(lightTypeName(s.lights[0].type), "rect");
    EXPECT_NEAR(s.lights[0].wsEmitNormal().y, -1.0, 1e-15);  // cross((1,0,0), (0,0,1)) = (0,-1,0)
}

TEST(SceneLoader, DegenerateTrianglesAreCountedNotDropped) {
    Scene s;
    MeshPrimitive m;
    m.wsPositions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    m.indices = {0, 1, 2, 0, 1, 3, 2, 2, 1};  // one good, one collinear, one with a repeated vertex
    s.meshes.push_back(m);
    finalizeScene(s);
    EXPECT_EQ(s.stats.triangles, 3u);
    EXPECT_EQ(s.stats.degenerateTriangles, 2u);
    EXPECT_EQ(s.meshes[0].indices.size(), 9u);
}

TEST(SceneLoader, ContentHashChangesWithReferencedFile) {
    const fs::path dir = fs::temp_directory_path() / "so_scene_hash_test";
    fs::create_directories(dir);
    fs::copy_file(kData / "valid" / "tri.gltf", dir / "tri.gltf",
                  fs::copy_options::overwrite_existing);
    fs::copy_file(kData / "valid" / "scene.json", dir / "scene.json",
                  fs::copy_options::overwrite_existing);
    std::string h1 = loadScene(dir / "scene.json").contentHash;
    EXPECT_EQ(h1, loadScene(dir / "scene.json").contentHash);
    std::ofstream(dir / "tri.gltf", std::ios::app) << "\n";
    EXPECT_NE(h1, loadScene(dir / "scene.json").contentHash);
}

}  // namespace
}  // namespace so
