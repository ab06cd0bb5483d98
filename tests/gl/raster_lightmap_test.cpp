// The lightmap technique against the oracle (ctest label "gl"; skipped with the reason where no EGL
// display or GL 4.5 context can be had): on a plane under a square occluder the error falls as the
// density rises and the atlas's memory grows as its square, exactly; a chart border crossing a
// shadow edge shows no seam beyond one texel with dilation (and one without); a dynamic caster's
// shadow is absent and counted, while the flag changes no other technique's image; TEXCOORD_1
// does what generated charts do; an area light's bake converges like accumulate; the bake's time
// is reported apart from the frame's, through raster.json and metrics.json.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "core/channels.h"
#include "core/error.h"
#include "core/lights/make_light.h"
#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"
#include "test_scenes.h"

namespace so::test {
namespace {

namespace ch = channels;
namespace fs = std::filesystem;

// A 4 x 4 plane at y = 0 (one quad, or two side by side meeting at x = 0: two meshes, so two
// charts), a square of side 1 at height 1 turned by `turnDeg` about y, a directional light, and a
// camera looking down on it.
Scene planeUnderSquare(double turnDeg, const glm::dvec3& lightDirection, bool splitPlane, int size,
                       double vfovDeg = 40.0) {
    Scene s;
    if (splitPlane) {
        s.meshes.push_back(makeGrid({-1, 0, 0}, {2, 0, 0}, {0, 0, -4}, 1, "left"));
        s.meshes.push_back(makeGrid({1, 0, 0}, {2, 0, 0}, {0, 0, -4}, 1, "right"));
    } else {
        s.meshes.push_back(makeGrid({0, 0, 0}, {4, 0, 0}, {0, 0, -4}, 1, "plane"));
    }
    const double a = turnDeg * std::numbers::pi / 180.0;
    s.meshes.push_back(makeGrid({0, 1, 0}, {std::cos(a), 0, std::sin(a)},
                                {std::sin(a), 0, -std::cos(a)}, 1, "square"));
    s.camera.wsEye = {0.0, 6.0, 0.5};
    s.camera.wsTarget = {0.0, 0.0, 0.0};
    s.camera.vfovDeg = vfovDeg;
    s.camera.width = s.camera.height = size;
    s.lights = {directionalLight("sun", glm::normalize(lightDirection))};
    s.effects = {"hard"};
    finalizeScene(s);
    return s;
}

double maeOf(const ChannelImage& oracle, const ChannelImage& raster, const std::string& light) {
    return computeLightMetrics(oracle, raster, light, {}).mae;
}

int64_t count(const RasterResult& r, const char* name) {
    return r.stats.lights.at(0).counts.at(name);
}

// Error falls as density rises (16 to 256 texels a unit), and the memory: the atlas is a byte a
// texel, plus 32 bytes a triangle and 4 a mesh for the lookup's table, exactly; with the square
// left out (dynamic) and no padding, the atlas is the plane's (4 d)^2 texels: d squared, exactly.
TEST(Lightmap, ErrorFallsAsDensityRisesAndMemoryGrowsAsItsSquare) {
    REQUIRE_GL();
    const Scene s = planeUnderSquare(23.0, {0.3, -1.0, 0.2}, false, 192);
    const ChannelImage oracle = runQuiet(s);
    std::vector<double> errors;
    for (int d : {16, 32, 64, 128, 256}) {
        const RasterResult r = renderOneFrame(
            s, "lightmap", {"texels_per_unit=" + std::to_string(d), "bake_resolution=4096"});
        errors.push_back(maeOf(oracle, r.image, "sun"));
        const uint64_t texels = uint64_t(count(r, "atlas_width") * count(r, "atlas_height"));
        std::printf("[ lightmap ] %3d texels/unit: mae %.5f, atlas %lld x %lld, %llu bytes\n", d,
                    errors.back(), (long long)count(r, "atlas_width"),
                    (long long)count(r, "atlas_height"),
                    (unsigned long long)r.stats.lights[0].memoryBytes);
        EXPECT_EQ(count(r, "atlas_bytes"), int64_t(texels));
        // The atlas, the light's table (4 triangles, 2 meshes) and its V and aliasing targets.
        EXPECT_EQ(r.stats.lights[0].memoryBytes, texels + 4 * 32 + 2 * 4 + 192 * 192 * 8);
        if (errors.size() > 1) {
            EXPECT_LT(errors.back(), errors[errors.size() - 2]) << d;
        }
    }
    EXPECT_LT(errors.back(), errors.front() / 4);

    Scene alone = s;
    alone.meshes[1].dynamic = true;
    uint64_t first = 0;
    for (int d : {16, 32, 64, 128, 256}) {
        const RasterResult r = renderOneFrame(
            alone, "lightmap", {"texels_per_unit=" + std::to_string(d), "padding=0", "dilate=0"});
        EXPECT_EQ(count(r, "atlas_bytes"), 16 * d * d);
        const uint64_t bytes = r.stats.lights[0].memoryBytes;
        if (d == 16) first = bytes;
        EXPECT_EQ(bytes - first, uint64_t(16 * (d * d - 16 * 16))) << d;
    }
}

// The distance from (x, z) to the boundary of the square [-0.5, 0.5]^2.
double toSquareEdge(double x, double z) {
    const double dx = std::fabs(x) - 0.5, dz = std::fabs(z) - 0.5;
    if (dx <= 0 && dz <= 0) return std::min(-dx, -dz);
    return std::hypot(std::max(dx, 0.0), std::max(dz, 0.0));
}

// The plane in two charts meeting at x = 0, the square's shadow (light straight down: the square
// [-0.5, 0.5]^2 on the floor) crossing that border. Near the border and more than one texel from
// the shadow's edge, V must be the oracle's: with dilation it is (up to 0.02), without it the
// bilinear lookup reads the empty padding beside each chart, a dark seam along the border.
TEST(Lightmap, NoSeamAtAChartBorderBeyondOneTexelWithDilation) {
    REQUIRE_GL();
    const Scene s = planeUnderSquare(0.0, {0.0, -1.0, 0.0}, true, 256, 26.0);
    const ChannelImage oracle = runQuiet(s);
    const double texel = 1.0 / 16;
    auto worstNearBorder = [&](int dilate, size_t& pixels) {
        const RasterResult r =
            renderOneFrame(s, "lightmap",
                           {"texels_per_unit=16", "padding=2", "dilate=" + std::to_string(dilate),
                            "bake_resolution=4096"});
        const float* Vr = r.image.channel(ch::lightChannel("sun", ch::kVisibility));
        const float* Vo = oracle.channel(ch::lightChannel("sun", ch::kVisibility));
        const float* Px = oracle.channel(ch::kPX);
        const float* Pz = oracle.channel(ch::kPZ);
        const float* mesh = oracle.channel(ch::kMeshId);
        double worst = 0.0;
        pixels = 0;
        for (size_t i = 0; i < oracle.pixelCount(); ++i) {
            if (mesh[i] > 1.0f || std::fabs(Px[i]) > 1.5 * texel) continue;  // the plane's border
            if (toSquareEdge(Px[i], Pz[i]) <= texel) continue;
            ++pixels;
            worst = std::max(worst, double(std::fabs(Vr[i] - Vo[i])));
        }
        return worst;
    };
    size_t with = 0, without = 0;
    const double dilated = worstNearBorder(2, with), bare = worstNearBorder(0, without);
    std::printf(
        "[ lightmap ] largest error within 1.5 texels of the border, beyond one of the "
        "shadow's edge: %.4f dilated, %.4f not (%zu pixels)\n",
        dilated, bare, with);
    ASSERT_GT(with, 500u);
    EXPECT_LT(dilated, 0.02);
    EXPECT_GT(bare, 0.3) << "no seam without dilation: the test would not see one";
}

// A caster marked dynamic is not baked: its shadow is gone (every floor pixel the oracle shadows
// is lit) and raster.json counts it; the oracle and another technique do not see the flag at all
// (bit-identical images).
TEST(Lightmap, ADynamicCastersShadowIsAbsentAndCounted) {
    REQUIRE_GL();
    const Scene s = planeUnderSquare(23.0, {0.9, -1.0, 0.6}, false, 128);
    Scene moving = s;
    moving.meshes[1].dynamic = true;
    const ChannelImage oracle = runQuiet(s);
    const RasterResult still = renderOneFrame(s, "lightmap", {});
    const RasterResult gone = renderOneFrame(moving, "lightmap", {});
    EXPECT_EQ(count(still, "dynamic_casters_left_out"), 0);
    EXPECT_EQ(count(gone, "dynamic_casters_left_out"), 1);
    EXPECT_EQ(count(gone, "dynamic_triangles_left_out"), 2);
    const float* Vo = oracle.channel(ch::lightChannel("sun", ch::kVisibility));
    const float* mesh = oracle.channel(ch::kMeshId);
    const float* Vs = still.image.channel(ch::lightChannel("sun", ch::kVisibility));
    const float* Vg = gone.image.channel(ch::lightChannel("sun", ch::kVisibility));
    size_t shadowed = 0, litWhenGone = 0, shadowWhenStill = 0;
    for (size_t i = 0; i < oracle.pixelCount(); ++i) {
        if (mesh[i] != 0.0f || Vo[i] != 0.0f) continue;
        ++shadowed;
        litWhenGone += Vg[i] > 0.99f;
        shadowWhenStill += Vs[i] < 0.5f;
    }
    ASSERT_GT(shadowed, 500u);
    EXPECT_EQ(litWhenGone, shadowed);
    EXPECT_GT(shadowWhenStill, shadowed * 97 / 100);
    const LightMetrics m = computeLightMetrics(oracle, gone.image, "sun", {});
    EXPECT_GT(m.falseLitRate, 0.9 * double(shadowed) / double(m.counted));

    const ChannelImage oracleMoving = runQuiet(moving);
    const RasterResult pcf = renderOneFrame(s, "pcf", {"resolution=512"}),
                       pcfMoving = renderOneFrame(moving, "pcf", {"resolution=512"});
    for (const std::string& name : oracle.names()) {
        EXPECT_EQ(std::memcmp(oracle.channel(name), oracleMoving.channel(name),
                              oracle.pixelCount() * sizeof(float)),
                  0)
            << "oracle " << name;
    }
    for (const std::string& name : pcf.image.names()) {
        EXPECT_EQ(std::memcmp(pcf.image.channel(name), pcfMoving.image.channel(name),
                              pcf.image.pixelCount() * sizeof(float)),
                  0)
            << "pcf " << name;
    }
}

// A plane laid out by its own TEXCOORD_1 (turned a quarter and mirrored) bakes and looks up as
// well as its generated chart does.
TEST(Lightmap, Texcoord1DoesWhatGeneratedChartsDo) {
    REQUIRE_GL();
    const Scene s = planeUnderSquare(23.0, {0.3, -1.0, 0.2}, false, 128);
    Scene own = s;
    for (const glm::dvec3& p : own.meshes[0].wsPositions)
        own.meshes[0].lightmapUvs.push_back({(p.z + 2.0) / 4.0, (p.x + 2.0) / 4.0});
    const ChannelImage oracle = runQuiet(s);
    const RasterResult generated = renderOneFrame(s, "lightmap", {"texels_per_unit=48"});
    const RasterResult uv1 = renderOneFrame(own, "lightmap", {"texels_per_unit=48"});
    EXPECT_EQ(count(uv1, "texcoord1_meshes"), 1);
    EXPECT_EQ(count(generated, "texcoord1_meshes"), 0);
    EXPECT_EQ(count(uv1, "texels_covered"), count(generated, "texels_covered"));
    const double a = maeOf(oracle, generated.image, "sun"), b = maeOf(oracle, uv1.image, "sun");
    std::printf("[ lightmap ] mae: generated chart %.5f, TEXCOORD_1 %.5f\n", a, b);
    EXPECT_LT(b, 1.5 * a + 1e-4);
    EXPECT_GT(b, a / 1.5 - 1e-4);
}

// An area light's bake is accumulate's estimator evaluated at texels: at a density well above the
// penumbra's, with the same samples, its penumbra error is accumulate's (the closed-form scene).
TEST(Lightmap, AnAreaLightsBakeConvergesLikeAccumulate) {
    REQUIRE_GL();
    const Scene s = makePenumbraScene(160, 120).scene;
    const ChannelImage oracle = runQuiet(s);
    const RasterResult lm = renderOneFrame(
        s, "lightmap", {"texels_per_unit=24", "bake_samples=64", "bake_resolution=1024"});
    const RasterResult acc =
        renderOneFrame(s, "accumulate", {"samples=64", "method=map", "resolution=1024"});
    const LightMetrics ml = computeLightMetrics(oracle, lm.image, "panel", {}),
                       ma = computeLightMetrics(oracle, acc.image, "panel", {});
    std::printf("[ lightmap ] penumbra mae: lightmap %.4f, accumulate %.4f (64 samples)\n",
                *ml.penumbraMae, *ma.penumbraMae);
    EXPECT_EQ(count(lm, "bake_samples"), 64);
    EXPECT_LT(*ml.penumbraMae, *ma.penumbraMae + 0.01);
    EXPECT_LT(ml.mae, ma.mae + 0.01);
}

// Triangles smaller than a texel, nearly none coplanar with a neighbour (one chart each, the
// fallback), most covering no texel's centre: each still gets the texel of its centroid, so an
// unshadowed bumpy plane is lit everywhere the light faces it (without the centroids, many of its
// triangles had no texel at all, V = 0 there, and no dilation could fill them).
TEST(Lightmap, EveryTriangleGetsATexelEvenSmallerThanOne) {
    REQUIRE_GL();
    Scene s;
    MeshPrimitive bumps = makeGrid({0, 0, 0}, {4, 0, 0}, {0, 0, -4}, 40, "bumps");
    for (glm::dvec3& p : bumps.wsPositions) p.y = 0.01 * std::sin(7.0 * p.x) * std::cos(5.0 * p.z);
    s.meshes.push_back(bumps);
    s.camera.wsEye = {0.0, 6.0, 0.5};
    s.camera.wsTarget = {0.0, 0.0, 0.0};
    s.camera.width = s.camera.height = 96;
    s.lights = {directionalLight("sun", {0, -1, 0})};
    s.effects = {"hard"};
    finalizeScene(s);
    const RasterResult r = renderOneFrame(s, "lightmap", {"texels_per_unit=4"});
    EXPECT_GT(count(r, "charts"), 3000) << "nearly every triangle a chart of its own";
    EXPECT_GT(count(r, "texels_from_centroids"), 1600);
    const float* V = r.image.channel(ch::lightChannel("sun", ch::kVisibility));
    const float* A = r.image.channel(ch::kHit);
    size_t hit = 0, dark = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        hit += A[i] != 0.0f;
        dark += A[i] != 0.0f && V[i] < 0.99f;
    }
    ASSERT_GT(hit, 5000u);
    EXPECT_EQ(dark, 0u);
}

// A density whose atlas would pass the limit is an input error naming texels_per_unit.
TEST(Lightmap, AnAtlasOverTheLimitNamesTheParameter) {
    REQUIRE_GL();
    const Scene s = planeUnderSquare(0.0, {0.0, -1.0, 0.0}, false, 32);
    try {
        renderOneFrame(s, "lightmap", {"texels_per_unit=2048"});
        ADD_FAILURE() << "an atlas of 17 x 2048^2 texels was made";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("technique lightmap: texels_per_unit:"),
                  std::string::npos)
            << e.what();
    }
}

// Through the command line, with the flag in a scene file: raster.json has the bake apart from the
// frame (bake_ms, its "bake.*" passes, only "visibility" among the frame's passes) and the dynamic
// caster counted; metrics.json has cost.bake_ms for the lightmap, null for a shadow map.
TEST(Lightmap, TheBakeIsReportedApartFromTheFrame) {
    REQUIRE_GL();
    const fs::path dir = fs::temp_directory_path() / "so_lightmap_cli_test";
    fs::remove_all(dir);
    fs::create_directories(dir / "meshes");
    for (const char* mesh : {"floor.gltf", "unit_box.gltf"})
        fs::copy_file(fs::path(SO_SCENES_DIR) / "meshes" / mesh, dir / "meshes" / mesh);
    std::ofstream(dir / "s.scene.json") << R"({"scene_format": 3,
        "geometry": [{"file": "meshes/floor.gltf"},
                     {"file": "meshes/unit_box.gltf", "scale": [2, 1.5, 2]},
                     {"file": "meshes/unit_box.gltf", "translate": [3, 0, 0], "dynamic": true}],
        "camera": {"eye": [-5.5, 4, -6], "target": [0, 0.5, 0], "width": 96, "height": 72},
        "lights": [{"name": "key", "type": "point", "position": [3, 5, 2.5]}]})";
    const RunResult r =
        run("compare " + (dir / "s.scene.json").string() +
            " --technique lightmap:texels_per_unit=8 --technique basic:resolution=256"
            " --frames 2 --no-cache --out " +
            (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const nlohmann::json raster = nlohmann::json::parse(
        readBytes(dir / "out" / "lightmap_texels_per_unit_8" / "raster.json"));
    const nlohmann::json& light = raster["lights"][0];
    EXPECT_EQ(light["passes"], nlohmann::json::array({"visibility"}));
    EXPECT_GT(light["bake_ms"].get<double>(), 0.0);
    for (const char* pass : {"bake.charts", "bake.shadow_map", "bake.texels", "bake.visibility",
                             "bake.weights", "bake.dilate", "bake.store"})
        EXPECT_TRUE(light["bake_passes_ms"].contains(pass)) << pass;
    EXPECT_EQ(light["counts"]["dynamic_casters_left_out"], 1);
    EXPECT_EQ(light["counts"]["dynamic_triangles_left_out"], 12);
    const nlohmann::json metrics = nlohmann::json::parse(readBytes(dir / "out" / "metrics.json"));
    for (const nlohmann::json& result : metrics["results"]) {
        const nlohmann::json& cost = result["lights"]["key"]["cost"];
        if (result["technique"] == "lightmap") {
            EXPECT_EQ(cost["bake_ms"].get<double>(), light["bake_ms"].get<double>());
        } else {
            EXPECT_TRUE(cost["bake_ms"].is_null());
        }
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so::test
