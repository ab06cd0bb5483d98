// Case 5 (docs/hard-cases.md): degenerate input. Zero-area and needle triangles, triangles
// degenerate in double but not once rounded to float, duplicated and coplanar triangles on the
// receiver, a light inside a closed box, a camera inside one, vertices at 1e30, a light on the
// receiver's surface.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "core/channels.h"
#include "core/error.h"
#include "core/lights/make_light.h"
#include "core/local_frame.h"
#include "hard_scenes.h"
#include "test_scenes.h"

namespace so::test::hard {
namespace {

namespace ch = channels;

struct VCount {
    size_t hits = 0, lit = 0, shadowed = 0;
};

VCount countV(const ChannelImage& img, const std::string& light, int meshFilter = -1) {
    const float* A = img.channel(ch::kHit);
    const float* mesh = img.channel(ch::kMeshId);
    const float* V = img.channel(ch::lightChannel(light, ch::kVisibility));
    VCount n;
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        if (A[i] == 0.0f || (meshFilter >= 0 && mesh[i] != float(meshFilter))) continue;
        ++n.hits;
        ++(V[i] == 1.0f ? n.lit : n.shadowed);
    }
    return n;
}

Scene floorScene(int size) {
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 8, "floor"));
    s.camera.wsEye = {0.5, 10.0, 6.0};
    s.camera.wsTarget = {0.0, 0.0, 0.0};
    s.camera.width = s.camera.height = size;
    return s;
}

// Vertices at 1e30 must be an InputError: built in code (finalizeScene) and through the loader
// (a scene file placing a glTF there). Before the check the oracle ran without a word and rounded
// the floor (size 16) to a point in its float frame: 0 pixels hit, every light V = 0.
TEST(HardDegenerate, VerticesAt1e30AreAnInputError) {
    Scene s = floorScene(64);
    s.meshes.push_back(makeBox({1e30, 0, 0}, {1e30 + 1e15, 1e15, 1e15}, "far"));
    s.lights.push_back(pointLight("key", {0.5, 4, 0.25}));
    std::string inCode = "(none)", loaded = "(none)";
    try {
        finalizeScene(s);
    } catch (const InputError& e) {
        inCode = e.what();
    }
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("so_hard_1e30_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::filesystem::copy_file(SO_TEST_DATA_DIR "/valid/tri.gltf", dir / "tri.gltf",
                               std::filesystem::copy_options::overwrite_existing);
    std::ofstream(dir / "far.scene.json")
        << R"({"scene_format": 1, "geometry": [{"file": "tri.gltf"},)"
        << R"( {"file": "tri.gltf", "translate": [1e30, 0, 0]}],)"
        << R"( "lights": [{"name": "key", "type": "point", "position": [0, 4, 0]}]})";
    try {
        loadScene(dir / "far.scene.json");
    } catch (const InputError& e) {
        loaded = e.what();
    }
    std::filesystem::remove_all(dir);
    std::printf("[ hard ] vertices at 1e30: in code: %s; loaded: %s\n", inCode.c_str(),
                loaded.c_str());
    EXPECT_NE(inCode.find("geometry"), std::string::npos);
    EXPECT_NE(loaded.find("far.scene.json: geometry"), std::string::npos);
    // At the limit itself a scene is accepted.
    Scene ok = floorScene(16);
    ok.meshes.push_back(makeBox({kMaxCoordinate - 0x1.0p10, 0, 0}, {kMaxCoordinate, 1, 1}, "far"));
    EXPECT_NO_THROW(finalizeScene(ok));
}

// 2D (x, z) distance from q to the segment a-b.
double segmentDistance2d(const glm::dvec2& q, const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 d = b - a;
    const double t = std::clamp(glm::dot(q - a, d) / glm::dot(d, d), 0.0, 1.0);
    return glm::length(q - (a + t * d));
}

// Occluders in the plane y = 2, over the floor, lit straight down: a square (2 triangles), two
// zero-area triangles (a repeated vertex; three collinear dyadic points) and two needles 2^-30 and
// 2^-20 wide. Zero-area triangles cast nothing; the square's shadow is exact; a needle's shadow is
// thinner than the blind distance, so pixels within it of a needle may go either way.
TEST(HardDegenerate, ZeroAreaAndNeedleTriangles) {
    Scene s = floorScene(128);
    MeshPrimitive m = makeGrid({0, 2, 0}, {2, 0, 0}, {0, 0, -2}, 1, "square");
    const std::vector<glm::dvec3> extra = {{3, 2, -3},
                                           {3, 2, -3},
                                           {5, 2, -2},  // repeated vertex
                                           {-3, 2, -3},
                                           {-2, 2, -3.5},
                                           {-1, 2, -4},  // collinear
                                           {2, 2, 2},
                                           {6, 2, 2},
                                           {4, 2, 2 + 0x1.0p-30},  // needle
                                           {-6, 2, 3},
                                           {-2, 2, 3 + 0x1.0p-20},
                                           {-2, 2, 3}};  // needle
    for (const glm::dvec3& p : extra) {
        m.indices.push_back(uint32_t(m.wsPositions.size()));
        m.wsPositions.push_back(p);
    }
    s.meshes.push_back(m);
    s.lights.push_back(directionalLight("down", {0, -1, 0}));
    finalizeScene(s);
    OracleResult r = runHard(s);
    const double tol = 2.0 * r.stats.offsetPolicy.maxBlindDistance;
    const float* A = r.image.channel(ch::kHit);
    const float* mesh = r.image.channel(ch::kMeshId);
    const float* V = r.image.channel(ch::lightChannel("down", ch::kVisibility));
    size_t checked = 0, nearNeedle = 0, shadowed = 0, wrong = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (A[i] == 0.0f || mesh[i] != 0.0f) continue;
        const glm::dvec3 p = hitPoint(r.image, i);
        const glm::dvec2 q(p.x, p.z);
        const double dSquare = std::max(std::fabs(q.x), std::fabs(q.y)) - 1.0;
        const double dNeedle =
            std::min(segmentDistance2d(q, {2, 2}, {6, 2}), segmentDistance2d(q, {-6, 3}, {-2, 3}));
        if (std::fabs(dSquare) < tol) continue;
        if (dNeedle < tol) {
            ++nearNeedle;
            continue;
        }
        ++checked;
        shadowed += dSquare < 0.0;
        wrong += V[i] != (dSquare < 0.0 ? 0.0f : 1.0f);
    }
    std::printf(
        "[ hard ] degenerate: %zu zero-area triangles counted; %zu floor px checked (%zu "
        "in the square's shadow), %zu wrong, %zu within the tolerance of a needle; %zu "
        "non-finite values\n",
        s.stats.degenerateTriangles, checked, shadowed, wrong, nearNeedle,
        nonFiniteValues(r.image));
    EXPECT_EQ(s.stats.degenerateTriangles, 2u);
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(shadowed, 200u);
    EXPECT_EQ(nonFiniteValues(r.image), 0u);
}

// Duplicated and coplanar triangles on the receiver: an exact copy of the floor (mesh 1) and a
// coplanar square tessellated differently (mesh 2). Documented (docs/oracle.md, offset policy):
// the origin offset clears coplanar neighbours and duplicates, so they shadow nothing, at normal
// and at grazing incidence.
TEST(HardDegenerate, DuplicatedAndCoplanarTrianglesOnTheReceiver) {
    Scene s = floorScene(128);
    s.meshes.push_back(s.meshes[0]);
    s.meshes[1].name = "floor copy";
    s.meshes.push_back(makeGrid({0.25, 0, -0.5}, {5, 0, 0}, {0, 0, -3}, 3, "coplanar square"));
    const double c = 1e-3, sn = std::sqrt(1.0 - c * c);
    s.lights.push_back(directionalLight("sun", {-0.6, -0.8, 0}));
    s.lights.push_back(directionalLight("grazing", {-sn, -c, 0}));
    s.lights.push_back(pointLight("lamp", {1.5, 3, 0.75}));
    finalizeScene(s);
    OracleResult r = runHard(s);
    size_t perMesh[3] = {countV(r.image, "sun", 0).hits, countV(r.image, "sun", 1).hits,
                         countV(r.image, "sun", 2).hits};
    for (const Light& l : s.lights) {
        const VCount n = countV(r.image, l.name);
        std::printf(
            "[ hard ] duplicates: %-7s %zu hit px, %zu lit, %zu shadowed (primary hits "
            "on floor / copy / coplanar square: %zu / %zu / %zu)\n",
            l.name.c_str(), n.hits, n.lit, n.shadowed, perMesh[0], perMesh[1], perMesh[2]);
        EXPECT_EQ(n.shadowed, 0u) << l.name;
        EXPECT_EQ(n.hits, r.image.pixelCount()) << l.name;
    }
    EXPECT_GT(perMesh[1] + perMesh[2], 0u) << "the duplicates must be seen somewhere";
}

// A point light inside a closed box standing on the floor: every pixel is V = 0 (the floor
// occluded, the box's outside faces away from the light).
TEST(HardDegenerate, LightInsideAClosedBox) {
    Scene s = floorScene(96);
    s.meshes.push_back(makeBox({-1, 0, -1}, {1, 2, 1}, "box"));
    s.lights.push_back(pointLight("inside", {0.25, 1, -0.125}));
    finalizeScene(s);
    OracleResult r = runHard(s);
    const VCount n = countV(r.image, "inside");
    const HardShadowStats& h = *r.stats.lights[0].hard;
    std::printf(
        "[ hard ] light inside a box: %zu hit px, %zu lit; %llu rays traced, %llu "
        "occluded, %llu attached\n",
        n.hits, n.lit, (unsigned long long)h.raysTraced, (unsigned long long)h.raysOccluded,
        (unsigned long long)h.skippedAttached);
    EXPECT_EQ(n.lit, 0u);
    EXPECT_EQ(h.raysOccluded, h.raysTraced);
    EXPECT_GT(h.raysTraced, 1000u);
    EXPECT_GT(h.skippedAttached, 500u);
}

// A camera inside a closed room with a cube on its floor: a light inside the room lights the
// inside faces (normals towards the camera) except the cube's exact shadow; a light outside the
// room reaches nothing.
TEST(HardDegenerate, CameraInsideAClosedMesh) {
    Scene s;
    s.meshes.push_back(makeBox({-4, 0, -4}, {4, 4, 4}, "room"));
    s.meshes.push_back(makeBox({-0.5, 0, -0.5}, {0.5, 1, 0.5}, "cube"));
    s.camera.wsEye = {0.5, 2.5, 3.25};
    s.camera.wsTarget = {0, 0.5, 0};
    s.camera.vfovDeg = 90;
    s.camera.width = s.camera.height = 128;
    const glm::dvec3 lamp(1.5, 3.5, 1.0);
    s.lights.push_back(pointLight("lamp", lamp));
    s.lights.push_back(pointLight("outside", {0.5, 10, 0.25}));
    finalizeScene(s);
    OracleResult r = runHard(s);
    const double tol = 2.0 * r.stats.offsetPolicy.maxBlindDistance;
    const float* mesh = r.image.channel(ch::kMeshId);
    const float* V = r.image.channel(ch::lightChannel("lamp", ch::kVisibility));
    size_t checked = 0, shadowed = 0, wrong = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (mesh[i] != 0.0f) continue;  // the room's inside
        const glm::dvec3 p = hitPoint(r.image, i);
        const glm::dvec3 lo(-0.5, 0, -0.5), hi(0.5, 1, 0.5);
        if (boxMargin(p, lamp, lo, hi, 1.0) < tol) continue;
        const bool occluded = segmentHitsBox(p, lamp, lo, hi, 0.0);
        ++checked;
        shadowed += occluded;
        wrong += V[i] != (occluded ? 0.0f : 1.0f);
    }
    const VCount lamp0 = countV(r.image, "lamp"), out = countV(r.image, "outside");
    std::printf(
        "[ hard ] camera inside a room: %zu hit px; inside light: %zu room px checked "
        "(%zu in the cube's shadow), %zu wrong, %zu lit in all; outside light: %zu lit\n",
        lamp0.hits, checked, shadowed, wrong, lamp0.lit, out.lit);
    EXPECT_EQ(lamp0.hits, r.image.pixelCount());
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(shadowed, 50u);
    EXPECT_EQ(out.lit, 0u);
}

// A light on the receiver's surface: on the floor itself (n.l = 0 exactly: every floor pixel
// attached, V = 0), and on a wall standing on the floor (the segment ends on the wall and stops
// short of the light, so the wall does not shadow the floor on either side: V = 1; the wall's
// pixels are attached).
TEST(HardDegenerate, LightOnTheReceiverSurface) {
    Scene s = floorScene(128);
    s.meshes.push_back(makeGrid({0, 1, 0}, {2, 0, 0}, {0, 2, 0}, 2, "wall"));  // z = 0
    s.lights.push_back(pointLight("on_floor", {0.5, 0, 0.25}));
    s.lights.push_back(pointLight("on_wall", {0.25, 1, 0}));
    finalizeScene(s);
    OracleResult r = runHard(s);
    const VCount floorOnFloor = countV(r.image, "on_floor", 0);
    const VCount wallOnFloor = countV(r.image, "on_floor", 1);
    const VCount floorOnWall = countV(r.image, "on_wall", 0);
    const VCount wallOnWall = countV(r.image, "on_wall", 1);
    std::printf(
        "[ hard ] light on the floor: %zu floor px, %zu lit; light on the wall: %zu floor "
        "px, %zu lit; %zu wall px, %zu lit (floor light: %zu lit)\n",
        floorOnFloor.hits, floorOnFloor.lit, floorOnWall.hits, floorOnWall.lit, wallOnWall.hits,
        wallOnWall.lit, wallOnFloor.lit);
    EXPECT_GT(floorOnFloor.hits, 10000u);
    EXPECT_GT(wallOnWall.hits, 200u);
    EXPECT_EQ(floorOnFloor.lit, 0u);
    EXPECT_EQ(r.stats.lights[0].hard->skippedAttached, floorOnFloor.hits);
    EXPECT_EQ(r.stats.lights[1].hard->skippedAttached, wallOnWall.hits);
    EXPECT_EQ(floorOnWall.shadowed, 0u);
    EXPECT_EQ(wallOnWall.lit, 0u);
}

// Triangles that are exactly degenerate in double but not once rounded to float: c is the exact
// midpoint of a and b (coordinates on a 2^-36 grid, so a + b and the halving are exact), so the
// double cross product is exactly 0 and finalizeScene counts them as degenerate ("never hit"), but
// the three roundings to float are independent and Embree sees slivers about 1e-7 wide. 20,000 of
// them over the floor, lit from above: no channel may hold a NaN.
TEST(HardDegenerate, TrianglesDegenerateInDoubleButNotInFloat) {
    Scene s = floorScene(256);
    MeshPrimitive m;
    m.name = "slivers";
    uint64_t state = 12345;
    auto uniform = [&state]() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1.0p-53;
    };
    for (int t = 0; t < 20000; ++t) {
        const glm::dvec3 c(-3.0 + 6.0 * uniform(), 1.0 + uniform(), -3.0 + 6.0 * uniform());
        const glm::dvec3 d(uniform() - 0.5, 0.1 * (uniform() - 0.5), uniform() - 0.5);
        const glm::dvec3 a = snap(c - d, 36), b = snap(c + d, 36);
        for (const glm::dvec3& p : {a, b, 0.5 * (a + b)}) {
            m.indices.push_back(uint32_t(m.wsPositions.size()));
            m.wsPositions.push_back(p);
        }
    }
    s.meshes.push_back(m);
    s.lights.push_back(pointLight("lamp", {0.5, 6, 0.25}));
    finalizeScene(s);
    OracleResult r = runHard(s);
    const float* A = r.image.channel(ch::kHit);
    const float* mesh = r.image.channel(ch::kMeshId);
    const float* NX = r.image.channel(ch::kNX);
    size_t sliverPixels = 0, nanNormals = 0;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (A[i] == 0.0f || mesh[i] != 1.0f) continue;
        ++sliverPixels;
        nanNormals += std::isnan(NX[i]);
    }
    const size_t nonFinite = nonFiniteValues(r.image);
    std::printf(
        "[ hard ] slivers: %zu of 20000 counted degenerate; %zu px hit one, %zu with a NaN "
        "normal; %zu non-finite values in all\n",
        s.stats.degenerateTriangles, sliverPixels, nanNormals, nonFinite);
    EXPECT_EQ(s.stats.degenerateTriangles, 20000u);
    EXPECT_EQ(nonFinite, 0u);
}

}  // namespace
}  // namespace so::test::hard
