// Camera paths (scene_format 2): parsing, sampling (camera_path.h), and Camera::project as the
// inverse of generateRay, which temporal flicker tracking relies on. The path's input errors are in
// tests/data/broken_scene (scene_loader_test.cpp).
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/camera.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/scene.h"

namespace so {
namespace {

namespace fs = std::filesystem;
const fs::path kData = SO_TEST_DATA_DIR;

TEST(CameraPathLoad, KeyframesLoadExactly) {
    const Scene s = loadScene(kData / "valid" / "path_keyframes.json");
    ASSERT_TRUE(s.cameraPath);
    const CameraPath& p = *s.cameraPath;
    EXPECT_EQ(p.interpolation, PathInterpolation::CatmullRom);
    ASSERT_EQ(p.keyframes.size(), 3u);
    EXPECT_EQ(p.keyframes[1].t, 1.0);
    EXPECT_EQ(p.keyframes[1].wsEye, glm::dvec3(2, 3, 3));
    EXPECT_FALSE(p.keyframes[0].vfovDeg);
    EXPECT_EQ(p.keyframes[1].vfovDeg.value_or(0.0), 50.0);
    EXPECT_FALSE(p.keyframes[1].wsUp);
    EXPECT_EQ(p.keyframes[2].wsUp.value_or(glm::dvec3(0.0)), glm::dvec3(0, 1, 0.1));
    EXPECT_EQ(p.file, (kData / "valid" / "path_keyframes.json").string());
}

TEST(CameraPathLoad, PosesAreKeyframesAtConsecutiveT) {
    const Scene s = loadScene(kData / "valid" / "path_poses.json");
    ASSERT_TRUE(s.cameraPath);
    ASSERT_EQ(s.cameraPath->keyframes.size(), 3u);
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(s.cameraPath->keyframes[i].t, double(i));
    EXPECT_EQ(s.cameraPath->interpolation, PathInterpolation::Linear);
    // Three poses in three frames: each pose exactly.
    const std::vector<CameraDesc> c = sampleCameraPath(*s.cameraPath, s.camera, 3);
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c[1].wsEye, glm::dvec3(1, 3, 3));
    EXPECT_EQ(c[2].wsEye, glm::dvec3(1, 3, 2));
}

TEST(CameraPathLoad, FormatOneStillLoadsWithoutPath) {
    const Scene s = loadScene(kData / "valid" / "scene.json");
    EXPECT_FALSE(s.cameraPath);
}

TEST(CameraPathLoad, KeyframeCountIsBounded) {
    LoadLimits limits;
    limits.maxPathKeyframes = 2;
    try {
        loadScene(kData / "valid" / "path_keyframes.json", limits);
        FAIL() << "loaded 3 keyframes with a limit of 2";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("camera_path.keyframes: 3 entries, limit is 2"),
                  std::string::npos)
            << e.what();
    }
    limits.maxPathKeyframes = 3;
    EXPECT_NO_THROW(loadScene(kData / "valid" / "path_keyframes.json", limits));
}

// The path changes the content hash (the oracle cache keys on it).
TEST(CameraPathLoad, PathIsInTheContentHash) {
    const fs::path dir = fs::temp_directory_path() / ("so_path_hash_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    fs::copy_file(kData / "valid" / "tri.gltf", dir / "tri.gltf",
                  fs::copy_options::overwrite_existing);
    std::ifstream in(kData / "valid" / "path_poses.json");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(dir / "a.json") << text;
    // The first 2 after "poses" is the last pose's eye z: moved to 7, still a valid path.
    std::string moved = text;
    const size_t two = moved.find('2', moved.find("\"poses\""));
    ASSERT_NE(two, std::string::npos);
    moved.replace(two, 1, "7");
    std::ofstream(dir / "b.json") << moved;
    const Scene a = loadScene(dir / "a.json"), b = loadScene(dir / "b.json");
    ASSERT_TRUE(a.cameraPath && b.cameraPath);
    EXPECT_NE(a.contentHash, b.contentHash);
    fs::remove_all(dir);
}

CameraPath twoKeys(PathInterpolation how) {
    CameraPath p;
    p.file = "test";
    p.interpolation = how;
    CameraKeyframe a, b;
    a.t = 1.0, a.wsEye = {0, 1, 5}, a.wsTarget = {0, 0, 0};
    b.t = 3.0, b.wsEye = {4, 1, 5}, b.wsTarget = {1, 0, 0}, b.vfovDeg = 60.0;
    p.keyframes = {a, b};
    return p;
}

TEST(CameraPathSample, EndpointsAreTheKeyframesExactly) {
    CameraDesc base;
    base.width = 33, base.height = 17, base.vfovDeg = 40.0;
    for (PathInterpolation how : {PathInterpolation::Linear, PathInterpolation::CatmullRom}) {
        const CameraPath p = twoKeys(how);
        const std::vector<CameraDesc> c = sampleCameraPath(p, base, 7);
        ASSERT_EQ(c.size(), 7u);
        EXPECT_EQ(c.front().wsEye, p.keyframes[0].wsEye);
        EXPECT_EQ(c.front().wsTarget, p.keyframes[0].wsTarget);
        EXPECT_EQ(c.front().vfovDeg, 40.0);  // the base's, where the key has none
        EXPECT_EQ(c.back().wsEye, p.keyframes[1].wsEye);
        EXPECT_EQ(c.back().wsTarget, p.keyframes[1].wsTarget);
        EXPECT_EQ(c.back().vfovDeg, 60.0);
        for (const CameraDesc& d : c) {
            EXPECT_EQ(d.width, 33);
            EXPECT_EQ(d.height, 17);
        }
    }
}

TEST(CameraPathSample, LinearMidpoint) {
    const std::vector<CameraDesc> c =
        sampleCameraPath(twoKeys(PathInterpolation::Linear), CameraDesc{}, 3);
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c[1].wsEye, glm::dvec3(2, 1, 5));
    EXPECT_EQ(c[1].wsTarget, glm::dvec3(0.5, 0, 0));
    EXPECT_DOUBLE_EQ(c[1].vfovDeg, 50.0);
}

TEST(CameraPathSample, CatmullRomPassesThroughEveryKeyAndIsSmooth) {
    CameraPath p;
    p.file = "test";
    p.interpolation = PathInterpolation::CatmullRom;
    const double ts[4] = {0.0, 1.0, 2.0, 4.0};
    const glm::dvec3 eyes[4] = {{0, 1, 5}, {3, 1, 5}, {3, 2, 2}, {-1, 1, 3}};
    for (int i = 0; i < 4; ++i) {
        CameraKeyframe k;
        k.t = ts[i], k.wsEye = eyes[i], k.wsTarget = {0, 0, 0};
        p.keyframes.push_back(k);
    }
    // 5 frames over [0, 4]: t = 0, 1, 2, 3, 4 hit keys 0, 1, 2 and 3.
    const std::vector<CameraDesc> c = sampleCameraPath(p, CameraDesc{}, 5);
    ASSERT_EQ(c.size(), 5u);
    EXPECT_EQ(c[0].wsEye, eyes[0]);
    EXPECT_EQ(c[1].wsEye, eyes[1]);
    EXPECT_EQ(c[2].wsEye, eyes[2]);
    EXPECT_EQ(c[4].wsEye, eyes[3]);
    // Not the linear path between keys 2 and 3 (a spline bends), yet continuous at a key.
    const glm::dvec3 linear = 0.5 * (eyes[2] + eyes[3]);
    EXPECT_GT(glm::length(c[3].wsEye - linear), 1e-3);
    const double e = 1e-7;
    const glm::dvec3 before = cameraAt(p, CameraDesc{}, 1.0 - e).wsEye,
                     after = cameraAt(p, CameraDesc{}, 1.0 + e).wsEye;
    EXPECT_LT(glm::length(after - before), 1e-5);
    // C1: the one-sided slopes agree at key 1.
    const glm::dvec3 slopeIn = (eyes[1] - cameraAt(p, CameraDesc{}, 1.0 - 1e-4).wsEye) / 1e-4,
                     slopeOut = (cameraAt(p, CameraDesc{}, 1.0 + 1e-4).wsEye - eyes[1]) / 1e-4;
    EXPECT_LT(glm::length(slopeIn - slopeOut), 1e-2);
}

TEST(CameraPathSample, DegenerateInterpolatedPoseIsAnInputError) {
    // Eye and target swap places: halfway they meet.
    CameraPath p;
    p.file = "scene.json";
    CameraKeyframe a, b;
    a.t = 0, a.wsEye = {0, 0, 1}, a.wsTarget = {0, 0, -1};
    b.t = 1, b.wsEye = {0, 0, -1}, b.wsTarget = {0, 0, 1};
    p.keyframes = {a, b};
    try {
        sampleCameraPath(p, CameraDesc{}, 3);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scene.json: camera_path: at t = 0.5"),
                  std::string::npos)
            << e.what();
    }
}

TEST(CameraProject, InvertsGenerateRay) {
    CameraDesc d;
    d.wsEye = {1.5, 2.0, 7.0}, d.wsTarget = {-0.5, 0.3, 0.0}, d.wsUp = {0.1, 1.0, 0.0};
    d.vfovDeg = 55.0, d.width = 97, d.height = 61;
    const Camera camera(d);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 1000; ++k) {
        const double x = u(rng) * d.width, y = u(rng) * d.height, dist = 0.1 + 20.0 * u(rng);
        const Ray3d r = camera.generateRay(x, y);
        const std::optional<glm::dvec2> p = camera.project(r.origin + dist * r.direction);
        ASSERT_TRUE(p);
        EXPECT_NEAR(p->x, x, 1e-9);
        EXPECT_NEAR(p->y, y, 1e-9);
    }
    // Pixel centres land in their own pixel.
    const Ray3d r = camera.generateRay(12, 40);
    const glm::dvec2 p = *camera.project(r.origin + 3.0 * r.direction);
    EXPECT_EQ(int(std::floor(p.x)), 12);
    EXPECT_EQ(int(std::floor(p.y)), 40);
    // Behind the eye: none.
    EXPECT_FALSE(camera.project(d.wsEye - 2.0 * camera.wsForward()));
    EXPECT_FALSE(camera.project(d.wsEye));
}

}  // namespace
}  // namespace so
