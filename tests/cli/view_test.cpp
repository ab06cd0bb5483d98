// `shadow-oracle view` (docs/external.md): the matrices of view.json put every primary hit of
// gbuffer.exr on its own pixel centre in both conventions, gbuffer.exr's geometry is oracle.exr's
// bit for bit, and each light's shadow-map cameras contain the receivers they must.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "core/channels.h"
#include "core/image.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using so::test::run;

glm::dmat4 matrix(const json& a) {
    EXPECT_EQ(a.size(), 16u);
    glm::dmat4 m(0.0);
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = a[size_t(i)].get<double>();
    return m;
}

struct View {
    json j;
    so::ChannelImage gbuffer;
};

View makeView(const std::string& scene, int w, int h, const fs::path& out) {
    fs::remove_all(out);
    const auto r = run("view " SO_SCENES_DIR "/" + scene + " --out " + out.string() + " --width " +
                       std::to_string(w) + " --height " + std::to_string(h) + " --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    std::ifstream in(out / "view.json");
    return {json::parse(in), so::readExr((out / "gbuffer.exr").string())};
}

glm::dvec3 point(const so::ChannelImage& g, size_t i) {
    using namespace so::channels;
    return {g.channel(kPX)[i], g.channel(kPY)[i], g.channel(kPZ)[i]};
}

// Pixel positions of each covered P through proj * view; Vulkan's y runs down, OpenGL's up.
void expectOnPixelCentres(const View& v, bool vulkan) {
    const json& cam = v.j["camera"];
    const glm::dmat4 clipFromWorld =
        matrix(cam[vulkan ? "proj_vk" : "proj_gl"]) * matrix(cam[vulkan ? "view_vk" : "view_gl"]);
    const so::ChannelImage& g = v.gbuffer;
    const int W = g.width(), H = g.height();
    double worst = 0.0;
    size_t covered = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * size_t(W) + size_t(x);
            if (g.channel(so::channels::kHit)[i] == 0.0f) continue;
            ++covered;
            const glm::dvec4 clip = clipFromWorld * glm::dvec4(point(g, i), 1.0);
            ASSERT_GT(clip.w, 0.0);
            const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
            const double px = (ndc.x + 1.0) * 0.5 * W;
            const double py = (vulkan ? (ndc.y + 1.0) : (1.0 - ndc.y)) * 0.5 * H;
            worst = std::max({worst, std::abs(px - (x + 0.5)), std::abs(py - (y + 0.5))});
            EXPECT_GE(ndc.z, vulkan ? 0.0 : -1.0);
            EXPECT_LE(ndc.z, 1.0);
        }
    EXPECT_GT(covered, size_t(W * H / 4));
    // P is float32: its rounding moves it by about 1e-6 of its magnitude, 1e-4 pixel here.
    EXPECT_LT(worst, 1e-3) << (vulkan ? "proj_vk" : "proj_gl");
}

TEST(View, EveryHitProjectsOntoItsOwnPixelCentreInBothConventions) {
    const fs::path out = fs::temp_directory_path() / "so_view_project";
    for (const auto& [scene, w, h] : {std::tuple{"spot_objects.scene.json", 96, 72},
                                      std::tuple{"terrain_sun.scene.json", 64, 80},
                                      std::tuple{"penumbra_square.scene.json", 80, 60}}) {
        SCOPED_TRACE(scene);
        const View v = makeView(scene, w, h, out);
        EXPECT_EQ(v.j["view_format"], 1);
        EXPECT_EQ(v.j["camera"]["width"], w);
        EXPECT_EQ(v.j["camera"]["height"], h);
        expectOnPixelCentres(v, false);
        expectOnPixelCentres(v, true);
    }
    fs::remove_all(out);
}

TEST(View, GbufferGeometryIsTheOraclesBitForBit) {
    const fs::path out = fs::temp_directory_path() / "so_view_oracle";
    const View v = makeView("contact_box.scene.json", 72, 56, out / "view");
    const auto r = run("trace " SO_SCENES_DIR "/contact_box.scene.json --out " +
                       (out / "trace").string() + " --width 72 --height 56 --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const so::ChannelImage oracle = so::readExr((out / "trace" / "oracle.exr").string());
    using namespace so::channels;
    for (const char* c : {kHit, kPX, kPY, kPZ, kNX, kNY, kNZ, kDepth, kMeshId, kPrimId}) {
        SCOPED_TRACE(c);
        EXPECT_TRUE(std::equal(v.gbuffer.channel(c), v.gbuffer.channel(c) + oracle.pixelCount(),
                               oracle.channel(c),
                               [](float a, float b) { return std::memcmp(&a, &b, 4) == 0; }));
    }
    // The replay channels: barycentrics inside the triangle where a ray hit, 0 elsewhere.
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        const float u = v.gbuffer.channel(kBaryU)[i], w = v.gbuffer.channel(kBaryV)[i];
        EXPECT_TRUE(u >= 0.0f && w >= 0.0f && u + w <= 1.0f + 1e-6f) << i;
        if (oracle.channel(kHit)[i] == 0.0f) {
            EXPECT_EQ(u + w, 0.0f) << i;
        }
    }
    fs::remove_all(out);
}

// Whether a world point lies inside a face's clip volume (depth 0..1, as the raster path's maps).
bool insideFace(const json& face, const glm::dvec3& p) {
    const glm::dvec4 clip = matrix(face["proj"]) * matrix(face["view"]) * glm::dvec4(p, 1.0);
    if (clip.w <= 0.0) return false;
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    const double eps = 1e-9;
    return std::abs(ndc.x) <= 1.0 + eps && std::abs(ndc.y) <= 1.0 + eps && ndc.z >= -eps &&
           ndc.z <= 1.0 + eps;
}

TEST(View, LightCamerasContainTheReceiversTheyShadow) {
    const fs::path out = fs::temp_directory_path() / "so_view_lights";
    size_t checked = 0;
    for (const char* scene : {"spot_objects.scene.json", "terrain_sun.scene.json"}) {
        SCOPED_TRACE(scene);
        const View v = makeView(scene, 64, 48, out);
        for (const json& light : v.j["lights"]) {
            const std::string type = light["type"];
            const json& faces = light["light_space"];
            ASSERT_EQ(faces.size(), type == "point" ? 6u : 1u) << type;
            // A view matrix is rigid: world units in light space.
            for (const json& f : faces) {
                const glm::dmat4 view = matrix(f["view"]);
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(glm::length(glm::dvec3(view[c])), 1.0, 1e-12);
            }
            for (size_t i = 0; i < v.gbuffer.pixelCount(); ++i) {
                if (v.gbuffer.channel(so::channels::kHit)[i] == 0.0f) continue;
                const glm::dvec3 p = point(v.gbuffer, i);
                if (type == "spot") {
                    // Inside the cone: inside the map.
                    const glm::dvec3 pos(light["position"][0], light["position"][1],
                                         light["position"][2]);
                    const glm::dvec3 dir(light["direction"][0], light["direction"][1],
                                         light["direction"][2]);
                    const double cosOuter =
                        std::cos(light["outer_cone_deg"].get<double>() * M_PI / 180.0);
                    if (glm::dot(glm::normalize(p - pos), dir) < cosOuter) continue;
                }
                bool inside = false;
                for (const json& f : faces) inside = inside || insideFace(f, p);
                EXPECT_TRUE(inside) << light["name"] << " pixel " << i;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 3000u);
    fs::remove_all(out);
}

TEST(View, BadInputExitsTwoWithOneLine) {
    for (const std::string args : {"view /nonexistent/scene.json --out /tmp/so_view_bad",
                                   "view " SO_SCENES_DIR "/contact_box.scene.json --out "
                                   "/proc/so_view_cannot_write"}) {
        const auto r = run(args + " --quiet");
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;
    }
}

}  // namespace

namespace {

// gbuffer.exr of `view` fed back to `trace --points`: every pixel replayed exactly, and every
// channel of oracle.exr but the points' own identical to a plain trace (hard lights and, with the
// same seed, sampled area lights bit for bit).
TEST(View, GbufferBackThroughTracePointsGivesThePlainTrace) {
    const fs::path out = fs::temp_directory_path() / "so_view_points";
    for (const char* scene : {"spot_objects.scene.json", "penumbra_square.scene.json"}) {
        SCOPED_TRACE(scene);
        const View v = makeView(scene, 64, 48, out / "view");
        const std::string s = std::string(SO_SCENES_DIR "/") + scene;
        auto r = run("trace " + s + " --out " + (out / "plain").string() +
                     " --width 64 --height 48 --quiet");
        ASSERT_EQ(r.exitCode, 0) << r.stderrText;
        r = run("trace " + s + " --points " + (out / "view" / "gbuffer.exr").string() + " --out " +
                (out / "points").string() + " --quiet");
        ASSERT_EQ(r.exitCode, 0) << r.stderrText;
        const so::ChannelImage plain = so::readExr((out / "plain" / "oracle.exr").string());
        const so::ChannelImage points = so::readExr((out / "points" / "oracle.exr").string());
        size_t compared = 0;
        for (const std::string& c : plain.names()) {
            SCOPED_TRACE(c);
            ASSERT_TRUE(points.has(c));
            EXPECT_EQ(std::memcmp(plain.channel(c), points.channel(c), plain.pixelCount() * 4), 0);
            ++compared;
        }
        EXPECT_GE(compared, 11u);
        const float* status = points.channel(so::channels::kPointsStatus);
        for (size_t i = 0; i < points.pixelCount(); ++i)
            EXPECT_EQ(status[i], plain.channel(so::channels::kHit)[i] != 0.0f ? 1.0f : 0.0f) << i;
        fs::remove_all(out);
    }
}

}  // namespace
