// Light paths (scene_format 5, docs/scene-format.md#light-paths): a light posed at a time, and
// the scene posed with it; the bad inputs are in tests/data/broken_scene (light_path_*).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/light_path.h"
#include "core/lights/make_light.h"
#include "core/scene_pose.h"

namespace so {
namespace {

LightPath positionPath(PathInterpolation how, std::vector<std::pair<double, glm::dvec3>> keys) {
    LightPath p;
    p.light = "l";
    p.interpolation = how;
    for (const auto& [t, at] : keys) p.keyframes.push_back({t, at, std::nullopt});
    return p;
}

TEST(LightPath, LinearMidpointAndClampingOutsideTheKeys) {
    const LightPath p =
        positionPath(PathInterpolation::Linear, {{1.0, {0, 4, 0}}, {3.0, {2, 4, -6}}});
    const Light l = pointLight("l", {9, 9, 9});
    EXPECT_EQ(lightAt(p, l, 2.0).wsPosition, glm::dvec3(1, 4, -3));
    EXPECT_EQ(lightAt(p, l, 0.0).wsPosition, glm::dvec3(0, 4, 0));
    EXPECT_EQ(lightAt(p, l, 7.0).wsPosition, glm::dvec3(2, 4, -6));
}

// Catmull-Rom passes through every key, and on keys along a line at even spacing it is the line.
TEST(LightPath, CatmullRomThroughTheKeysAndExactOnALine) {
    const LightPath p = positionPath(PathInterpolation::CatmullRom,
                                     {{0.0, {0, 0, 0}}, {1.0, {1, 2, 0}}, {2.0, {2, 4, 0}}});
    const Light l = pointLight("l", {0, 0, 0});
    EXPECT_EQ(lightAt(p, l, 1.0).wsPosition, glm::dvec3(1, 2, 0));
    const glm::dvec3 q = lightAt(p, l, 0.25).wsPosition;
    EXPECT_NEAR(q.x, 0.25, 1e-12);
    EXPECT_NEAR(q.y, 0.5, 1e-12);
}

// An area light moves rigidly: its centre goes to the key, its edges stay as they are.
TEST(LightPath, AnAreaLightMovesRigidly) {
    const LightPath p =
        positionPath(PathInterpolation::Linear, {{0.0, {0, 3, 0}}, {1.0, {4, 3, 0}}});
    const Light rect = rectLight("l", {0, 3, 0}, {1, 0, 0}, {0, 0, 1});
    const Light moved = lightAt(p, rect, 0.5);
    EXPECT_EQ(moved.wsPosition, glm::dvec3(2, 3, 0));
    EXPECT_EQ(moved.wsU, rect.wsU);
    EXPECT_EQ(moved.wsV, rect.wsV);
}

// A sun turning from straight down to 45 degrees: halfway the lerp of the unit keys, renormalised,
// is the bisector, 22.5 degrees from each.
TEST(LightPath, ADirectionTurnsAndStaysUnit) {
    LightPath p;
    p.light = "sun";
    const glm::dvec3 down(0, -1, 0), slant = glm::normalize(glm::dvec3(1, -1, 0));
    p.keyframes = {{0.0, std::nullopt, down}, {2.0, std::nullopt, slant}};
    const Light sun = directionalLight("sun", down);
    const glm::dvec3 d = lightAt(p, sun, 1.0).wsDirection;
    EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(d, down), std::cos(std::numbers::pi / 8.0), 1e-12);
    EXPECT_NEAR(glm::dot(d, slant), std::cos(std::numbers::pi / 8.0), 1e-12);
}

TEST(LightPath, SceneAtTimeMovesOnlyTheLightOnThePath) {
    MeshPrimitive tri;
    tri.wsPositions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    tri.indices = {0, 1, 2};
    Scene s = sceneFromMemory(R"({"lights": [{"name": "l", "type": "point", "position": [0, 4, 0]},
        {"name": "k", "type": "point", "position": [5, 5, 5]}]})",
                              {tri});
    s.sequence = Sequence{4, 2.0, ""};
    s.lightPaths = {positionPath(PathInterpolation::Linear, {{0.0, {0, 4, 0}}, {1.0, {2, 4, 0}}})};
    EXPECT_TRUE(sceneMoves(s));
    const Scene posed = sceneAtTime(s, sequenceTime(*s.sequence, 1));
    EXPECT_EQ(posed.lights[0].wsPosition, glm::dvec3(1, 4, 0));
    EXPECT_EQ(posed.lights[1].wsPosition, glm::dvec3(5, 5, 5));
    EXPECT_TRUE(posed.lightPaths.empty());
    EXPECT_NE(posed.contentHash, s.contentHash);
}

}  // namespace
}  // namespace so
