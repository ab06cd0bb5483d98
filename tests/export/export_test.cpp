// `shadow-oracle export` (docs/export.md): the glb loaded back through the project's own loader
// holds the same triangles (each vertex the float rounding of the original's world position, bit
// for bit), the exported folder traced as a scene gives the same hard-light V bit for bit, the
// glb's structure says what docs/export.md promises (KHR_lights_punctual, the camera of view.json,
// the lights' names and area-light extras), the same scene exports to the same bytes, and a
// folder that cannot be written is a one-line error.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "core/channels.h"
#include "core/scene.h"
#include "core/scene_pose.h"
#include "oracle/oracle.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using so::test::readBytes;
using so::test::run;

constexpr int kWidth = 96, kHeight = 72;

fs::path exportScene(const std::string& scene, const std::string& name,
                     const std::string& extra = "") {
    const fs::path out = fs::temp_directory_path() / ("so_export_test_" + name);
    fs::remove_all(out);
    const auto r =
        run("export " + scene + " --out " + out.string() + " --width " + std::to_string(kWidth) +
            " --height " + std::to_string(kHeight) + " --quiet " + extra);
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    return out;
}

uint32_t le32(const std::string& b, size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

// The glb's JSON chunk, after checking the container: magic, version 2, total length, a JSON
// chunk then a BIN chunk, each 4-byte aligned.
json glbJson(const fs::path& glb) {
    const std::string b = readBytes(glb);
    EXPECT_GE(b.size(), 28u);
    if (b.size() < 28) return json();
    EXPECT_EQ(b.substr(0, 4), "glTF");
    EXPECT_EQ(le32(b, 4), 2u);
    EXPECT_EQ(le32(b, 8), b.size());
    const uint32_t jsonLength = le32(b, 12);
    EXPECT_EQ(le32(b, 16), 0x4E4F534Au);  // "JSON"
    EXPECT_EQ(jsonLength % 4, 0u);
    const size_t bin = 20 + size_t(jsonLength);
    EXPECT_LE(bin + 8, b.size());
    EXPECT_EQ(le32(b, bin + 4), 0x004E4942u);  // "BIN"
    EXPECT_EQ(bin + 8 + le32(b, bin), b.size());
    return json::parse(b.substr(20, jsonLength));
}

// What a float vertex can hold of `p`: each coordinate rounded to float, one at a time. GCC 12.2
// at -O3 dropped the double -> float -> double round trip of x and y when the three were converted
// in one expression (the object code copied them unchanged), so this test first passed nothing
// through float at all; a scalar function it does not inline keeps each conversion.
[[gnu::noinline]] double roundedToFloat(double d) {
    return static_cast<float>(d);
}
glm::dvec3 floatRounded(const glm::dvec3& p) {
    return {roundedToFloat(p.x), roundedToFloat(p.y), roundedToFloat(p.z)};
}

// Every triangle of `exported` is the one of `original` with the same id.mesh and id.prim, each
// vertex the float rounding of the original's world position, bit for bit. Returns the largest
// distance that rounding moved a vertex, relative to the scene's extent.
double expectSameTriangles(const so::Scene& original, const so::Scene& exported) {
    EXPECT_EQ(exported.meshes.size(), original.meshes.size());
    double worst = 0.0;
    for (size_t m = 0; m < std::min(original.meshes.size(), exported.meshes.size()); ++m) {
        const so::MeshPrimitive &a = original.meshes[m], &b = exported.meshes[m];
        EXPECT_EQ(b.triangleCount(), a.triangleCount()) << a.name;
        if (b.triangleCount() != a.triangleCount()) continue;
        size_t differ = 0;
        for (size_t i = 0; i < a.indices.size(); ++i) {
            const glm::dvec3 p = a.wsPositions[a.indices[i]], q = b.wsPositions[b.indices[i]];
            const glm::dvec3 rounded = floatRounded(p);
            differ += std::memcmp(&q, &rounded, sizeof q) != 0;
            worst = std::max(worst, glm::length(q - p));
            if (a.alpha && original.hasEffect("alpha") && a.alpha->texture >= 0) {
                EXPECT_EQ(std::memcmp(&b.uvs[b.indices[i]], &a.uvs[a.indices[i]], 8), 0);
            }
        }
        EXPECT_EQ(differ, 0u) << a.name;
        EXPECT_EQ(b.alpha.has_value(), a.alpha.has_value() && original.hasEffect("alpha"));
        if (b.alpha && a.alpha) {
            EXPECT_EQ(b.alpha->cutoff, a.alpha->cutoff);
            EXPECT_EQ(b.alpha->factor, a.alpha->factor);
            EXPECT_EQ(b.alpha->wrapS, a.alpha->wrapS);
            EXPECT_EQ(b.alpha->wrapT, a.alpha->wrapT);
            EXPECT_EQ(b.alpha->filter, a.alpha->filter);
        }
        EXPECT_EQ(b.doubleSided, a.doubleSided) << a.name;
    }
    EXPECT_EQ(exported.alphaTextures.size(), original.alphaTextures.size());
    for (size_t t = 0; t < std::min(original.alphaTextures.size(), exported.alphaTextures.size());
         ++t) {
        EXPECT_EQ(exported.alphaTextures[t].alpha, original.alphaTextures[t].alpha);
        EXPECT_EQ(exported.alphaTextures[t].encoded, original.alphaTextures[t].encoded);
    }
    return worst / std::max(original.wsBounds.extent(), 1e-300);
}

// The oracle on both scenes at the export's size: every punctual light's V bit for bit. Returns
// how many pixels of the (sampled) area lights' V differ, for the record.
size_t expectSameHardVisibility(const so::Scene& original, const so::Scene& exported) {
    so::OracleOptions o;
    o.width = kWidth;
    o.height = kHeight;
    o.threads = 2;
    const so::OracleResult a = so::runOracle(original, o), b = so::runOracle(exported, o);
    size_t areaDiffer = 0;
    for (const so::Light& l : original.lights) {
        const std::string v = so::channels::lightChannel(l.name, so::channels::kVisibility);
        const float *va = a.image.channel(v), *vb = b.image.channel(v);
        size_t differ = 0;
        for (size_t i = 0; i < a.image.pixelCount(); ++i)
            differ += std::memcmp(&va[i], &vb[i], sizeof(float)) != 0;
        if (so::isAreaLight(l.type) && original.hasEffect("penumbra"))
            areaDiffer += differ;
        else
            EXPECT_EQ(differ, 0u) << l.name << ": hard-light V differs";
    }
    return areaDiffer;
}

struct RoundTrip {
    double relativeRounding = 0.0;
    size_t areaPixelsDiffer = 0;
};

// frame >= 0: export --frame, against the scene posed at that frame of its sequence.
RoundTrip roundTrip(const std::string& scene, const std::string& name, int frame = -1) {
    const fs::path out =
        exportScene(scene, name, frame >= 0 ? "--frame " + std::to_string(frame) : "");
    const so::Scene loaded = so::loadScene(scene);
    const so::Scene original =
        frame >= 0 ? so::sceneAtTime(loaded, so::sequenceTime(*loaded.sequence, frame)) : loaded;
    const so::Scene exported = so::loadScene(out / "scene.scene.json");
    EXPECT_EQ(exported.effects, original.effects);
    EXPECT_EQ(exported.lights.size(), original.lights.size());
    RoundTrip r;
    r.relativeRounding = expectSameTriangles(original, exported);
    r.areaPixelsDiffer = expectSameHardVisibility(original, exported);
    std::cout << "[ export   ] " << name << ": vertices moved by float rounding up to "
              << r.relativeRounding
              << " of the scene's extent; area-light V pixels that differ: " << r.areaPixelsDiffer
              << "\n";
    return r;
}

TEST(Export, AlphaGrateRoundTrip) {  // an alpha-tested grate, a sun and a rect light
    roundTrip(SO_SCENES_DIR "/alpha_grate.scene.json", "alpha_grate");
}

TEST(Export, SpotObjectsRoundTrip) {  // scaled and moved meshes: float rounding, a spot and a point
    roundTrip(SO_SCENES_DIR "/spot_objects.scene.json", "spot_objects");
}

TEST(Export, SoftChairRoundTrip) {  // rect and sphere area lights
    roundTrip(SO_SCENES_DIR "/soft_chair.scene.json", "soft_chair");
}

TEST(Export, RealFernRoundTrip) {  // a real model (its scene draws the fronds opaque)
    roundTrip(SO_SCENES_DIR "/real/fern/fern.scene.json", "fern");
}

TEST(Export, RealTruckTownRoundTrip) {  // a node tree, an alpha-tested (BLEND) texture, 2 km wide
    roundTrip(SO_SCENES_DIR "/real/truck_town/truck_town.scene.json", "truck_town");
}

TEST(Export, WebpTextureRoundTrip) {  // a bare glTF whose mask is a WebP image
    roundTrip(SO_TEST_DATA_DIR "/gltf/webp_alpha.gltf", "webp");
    const json g = glbJson(fs::temp_directory_path() / "so_export_test_webp" / "scene.glb");
    EXPECT_EQ(g["extensionsRequired"], json::array({"EXT_texture_webp"}));
    EXPECT_EQ(g["images"][0]["mimeType"], "image/webp");
    EXPECT_EQ(g["textures"][0]["extensions"]["EXT_texture_webp"]["source"], 0);
}

// export --frame K of a sequence: the scene posed at frame K (the box has slid, so its triangles
// are not frame 0's), the same hard-light V bit for bit; a scene without a sequence, or a frame
// past its end, is a one-line error naming the flag or field.
TEST(Export, SequenceFrameRoundTrip) {
    const std::string scene = SO_SCENES_DIR "/sliding_box/sliding_box.scene.json";
    roundTrip(scene, "sliding_box_9", 9);
    const so::Scene atRest = so::loadScene(scene),
                    exported = so::loadScene(fs::temp_directory_path() /
                                             "so_export_test_sliding_box_9/scene.scene.json");
    EXPECT_FALSE(exported.sequence.has_value()) << "a posed frame, not the animation";
    bool moved = false;
    for (size_t m = 0; m < atRest.meshes.size(); ++m)
        moved = moved || exported.meshes[m].wsPositions != atRest.meshes[m].wsPositions;
    EXPECT_TRUE(moved) << "frame 9 is not the scene at rest";
    for (const auto& [args, says] : std::vector<std::pair<std::string, std::string>>{
             {"export " SO_SCENES_DIR "/contact_box.scene.json --frame 2", "sequence"},
             {"export " + scene + " --frame 999", "--frame"},
             {"export " + scene + " --frame x", "--frame"}}) {
        const auto r = run(args + " --out " +
                           (fs::temp_directory_path() / "so_export_bad").string() + " --quiet");
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
        EXPECT_NE(r.stderrText.find(says), std::string::npos) << r.stderrText;
    }
}

const json& nodeNamed(const json& gltf, const std::string& name) {
    static const json none;
    for (const json& n : gltf["nodes"])
        if (n.value("name", "") == name) return n;
    ADD_FAILURE() << "no node " << name;
    return none;
}

TEST(Export, GlbStructure) {
    const fs::path out = exportScene(SO_SCENES_DIR "/soft_chair.scene.json", "structure");
    const json g = glbJson(out / "scene.glb");
    const json view = json::parse(readBytes(out / "view.json"));
    EXPECT_EQ(g["asset"]["version"], "2.0");
    EXPECT_EQ(g["asset"]["extras"]["shadow_oracle"]["format_version"], 1);
    EXPECT_EQ(g["asset"]["extras"]["shadow_oracle"]["source_scene"],
              SO_SCENES_DIR "/soft_chair.scene.json");
    EXPECT_EQ(g["asset"]["extras"]["shadow_oracle"]["bounds"], view["scene"]["bounds"]);
    const json used = g["extensionsUsed"];
    EXPECT_NE(std::find(used.begin(), used.end(), "KHR_lights_punctual"), used.end());

    // The camera: exactly view.json's field of view, aspect and depth range.
    const json& cam = g["cameras"][0]["perspective"];
    const json& vcam = view["camera"];
    EXPECT_EQ(cam["yfov"].get<double>(), vcam["vfov_deg"].get<double>() * M_PI / 180.0);
    EXPECT_EQ(cam["aspectRatio"].get<double>(), double(kWidth) / double(kHeight));
    EXPECT_EQ(vcam["width"], kWidth);
    EXPECT_EQ(vcam["height"], kHeight);
    EXPECT_EQ(cam["znear"], vcam["near"]);
    EXPECT_EQ(cam["zfar"], vcam["far"]);
    EXPECT_TRUE(nodeNamed(g, "camera").contains("camera"));

    // One mesh node per scene primitive, in order, named as the scene names it.
    const so::Scene scene = so::loadScene(SO_SCENES_DIR "/soft_chair.scene.json");
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        EXPECT_EQ(g["nodes"][m]["name"], scene.meshes[m].name);

    // Each light on a node with the scene's name; area lights as stand-ins with their shape.
    const json& lights = g["extensions"]["KHR_lights_punctual"]["lights"];
    ASSERT_EQ(lights.size(), scene.lights.size());
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const so::Light& l = scene.lights[i];
        const json& node = nodeNamed(g, l.name);
        const int index = node["extensions"]["KHR_lights_punctual"]["light"];
        const json& gl = lights[size_t(index)];
        const json& ex = gl["extras"]["shadow_oracle"];
        EXPECT_EQ(gl["name"], l.name);
        EXPECT_EQ(ex["type"], so::lightTypeName(l.type));
        EXPECT_EQ(ex["center"], json::array({l.wsPosition.x, l.wsPosition.y, l.wsPosition.z}));
        EXPECT_GT(ex["size"].get<double>(), 0.0);
        if (std::string(so::lightTypeName(l.type)) == "rect") {
            EXPECT_EQ(gl["type"], "spot");
            EXPECT_EQ(ex["edge_u"], json::array({l.wsU.x, l.wsU.y, l.wsU.z}));
            EXPECT_EQ(ex["edge_v"], json::array({l.wsV.x, l.wsV.y, l.wsV.z}));
            const double outer = gl["spot"]["outerConeAngle"];
            EXPECT_GT(outer, 0.0);
            EXPECT_LT(gl["spot"]["innerConeAngle"].get<double>(), outer);
            EXPECT_LE(outer, 85.0 * M_PI / 180.0 + 1e-12);
        } else {
            EXPECT_EQ(gl["type"], "point");
            EXPECT_EQ(ex["radius"], l.radius);
            EXPECT_EQ(ex["size"], 2.0 * l.radius);
        }
    }

    // Loaded bare, the glb's lights come back under the same names (area lights as stand-ins).
    const so::Scene bare = so::loadScene(out / "scene.glb");
    ASSERT_EQ(bare.lights.size(), scene.lights.size());
    for (size_t i = 0; i < scene.lights.size(); ++i)
        EXPECT_EQ(bare.lights[i].name, scene.lights[i].name);
}

TEST(Export, SameSceneSameBytes) {
    const fs::path a = exportScene(SO_SCENES_DIR "/alpha_grate.scene.json", "bytes_a");
    const fs::path b =
        exportScene(SO_SCENES_DIR "/alpha_grate.scene.json", "bytes_b", "--threads 1");
    EXPECT_EQ(readBytes(a / "scene.glb"), readBytes(b / "scene.glb"));
    EXPECT_EQ(readBytes(a / "scene.scene.json"), readBytes(b / "scene.scene.json"));
    EXPECT_EQ(readBytes(a / "gbuffer.exr"), readBytes(b / "gbuffer.exr"));
}

TEST(Export, UnwritableFolderIsOneLineError) {
    const fs::path file = fs::temp_directory_path() / "so_export_test_a_file";
    { std::ofstream(file) << "not a folder"; }
    const auto r = run("export " SO_SCENES_DIR "/contact_box.scene.json --out " +
                       (file / "out").string() + " --quiet");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
    EXPECT_NE(r.stderrText.find((file / "out").string()), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find("cannot create the folder"), std::string::npos) << r.stderrText;
    fs::remove(file);

    // A folder that exists but where scene.glb cannot be written (it is a folder itself).
    const fs::path dir = fs::temp_directory_path() / "so_export_test_blocked";
    fs::remove_all(dir);
    fs::create_directories(dir / "scene.glb");
    const auto blocked =
        run("export " SO_SCENES_DIR "/contact_box.scene.json --out " + dir.string() + " --quiet");
    EXPECT_EQ(blocked.exitCode, 2);
    EXPECT_EQ(blocked.stderrText,
              (dir / "scene.glb").string() + ": cannot be written (Is a directory)\n");
    fs::remove_all(dir);
}

}  // namespace
