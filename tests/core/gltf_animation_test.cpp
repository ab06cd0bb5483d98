// glTF animations (issue 52, docs/scene-format.md#animations): the interpolations against their
// closed forms, clamping outside the keys, parent chains, the pose of a scene at a time, and
// the motion between two times.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/gltf_animation.h"
#include "core/scene.h"
#include "core/scene_pose.h"

namespace so {
namespace {

namespace fs = std::filesystem;
const fs::path kAnim = fs::path(SO_TEST_DATA_DIR) / "anim";

AnimationTrack track(AnimatedProperty p, AnimationInterpolation how, std::vector<double> times,
                     std::vector<glm::dvec4> values) {
    AnimationTrack t;
    t.property = p;
    t.interpolation = how;
    t.times = std::move(times);
    t.values = std::move(values);
    return t;
}

TEST(GltfAnimation, StepHoldsTheEarlierKeyUntilTheNext) {
    AnimationTrack t = track(AnimatedProperty::Translation, AnimationInterpolation::Step,
                             {0.0, 1.0, 2.0}, {{1, 0, 0, 0}, {5, 0, 0, 0}, {9, 0, 0, 0}});
    EXPECT_EQ(t.sample(0.0).x, 1.0);
    EXPECT_EQ(t.sample(0.999).x, 1.0);
    EXPECT_EQ(t.sample(1.0).x, 5.0);
    EXPECT_EQ(t.sample(1.5).x, 5.0);
}

TEST(GltfAnimation, LinearMidpointAndClampingOutsideTheKeys) {
    AnimationTrack t = track(AnimatedProperty::Scale, AnimationInterpolation::Linear, {1.0, 3.0},
                             {{1, 2, 3, 0}, {3, 6, 7, 0}});
    const glm::dvec4 mid = t.sample(2.0);
    EXPECT_DOUBLE_EQ(mid.x, 2.0);
    EXPECT_DOUBLE_EQ(mid.y, 4.0);
    EXPECT_DOUBLE_EQ(mid.z, 5.0);
    EXPECT_EQ(t.sample(-10.0), t.values.front());  // before the first key: the first value
    EXPECT_EQ(t.sample(0.5), t.values.front());
    EXPECT_EQ(t.sample(3.0), t.values.back());  // after the last: the last
    EXPECT_EQ(t.sample(1e9), t.values.back());
}

// A 90-degree turn about y, halfway: 45 degrees, whichever sign the second key's quaternion has
// (q and -q are one rotation: slerp takes the short way).
TEST(GltfAnimation, SlerpOfANinetyDegreeTurnAtHalfTimeIsFortyFive) {
    const double h = std::sqrt(0.5);
    for (double sign : {1.0, -1.0}) {
        AnimationTrack t = track(AnimatedProperty::Rotation, AnimationInterpolation::Linear,
                                 {0.0, 2.0}, {{0, 0, 0, 1}, sign * glm::dvec4(0, h, 0, h)});
        const glm::dvec4 q = t.sample(1.0);
        const double angle = 2.0 * std::acos(std::abs(q.w)) * 180.0 / std::numbers::pi;
        EXPECT_NEAR(angle, 45.0, 1e-9) << "sign " << sign;
        EXPECT_NEAR(glm::length(q), 1.0, 1e-12);
        EXPECT_NEAR(std::abs(q.y), std::sin(std::numbers::pi / 8.0), 1e-12);
    }
}

// Hermite with zero tangents: the smoothstep 3s^2 - 2s^3 of the values, which is the midpoint at
// s = 1/2 and, at s = 1/4, 5/32 of the way.
TEST(GltfAnimation, CubicSplineWithZeroTangentsIsSmoothstep) {
    const glm::dvec4 zero(0.0);
    AnimationTrack t = track(AnimatedProperty::Translation, AnimationInterpolation::CubicSpline,
                             {0.0, 4.0}, {zero, {2, 0, 0, 0}, zero, zero, {10, 0, 0, 0}, zero});
    EXPECT_DOUBLE_EQ(t.sample(2.0).x, 6.0);
    EXPECT_DOUBLE_EQ(t.sample(1.0).x, 2.0 + 8.0 * 5.0 / 32.0);
    EXPECT_EQ(t.sample(-1.0).x, 2.0);  // the value of the triple, not its tangent
    EXPECT_EQ(t.sample(5.0).x, 10.0);
}

// Tangents scale with the key interval: values 0 and 0 with out-tangent 1 at the first key
// follow dt * (s^3 - 2 s^2 + s), so doubling the interval doubles the bulge.
TEST(GltfAnimation, CubicSplineTangentsScaleWithTheKeyInterval) {
    for (double dt : {1.0, 2.0}) {
        const glm::dvec4 zero(0.0);
        AnimationTrack t = track(AnimatedProperty::Translation, AnimationInterpolation::CubicSpline,
                                 {0.0, dt}, {zero, zero, {1, 0, 0, 0}, zero, zero, zero});
        EXPECT_DOUBLE_EQ(t.sample(0.5 * dt).x, dt * 0.125);
    }
}

// A scene file beside a copy of the glTF, in the test's own temporary folder.
std::filesystem::path writeScene(const std::string& name, const std::string& gltf,
                                 const std::string& sequence) {
    const fs::path dir = fs::temp_directory_path() / ("so_anim_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    fs::copy_file(kAnim / gltf, dir / gltf, fs::copy_options::overwrite_existing);
    const fs::path path = dir / (name + ".json");
    std::ofstream(path) << R"({"scene_format": 5, "geometry": [{"file": ")" << gltf
                        << R"("}], "lights": [{"name": "sun", "type": "directional",
        "direction": [0, -1, 0]}])"
                        << sequence << "}";
    return path;
}

glm::dvec3 centroid(const MeshPrimitive& m) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& p : m.wsPositions) sum += p;
    return sum / double(m.wsPositions.size());
}

TEST(GltfAnimation, WithoutASequenceAFileLoadsInItsNodesOwnPose) {
    Scene s = loadScene(writeScene("still", "sliding_box.gltf", ""));
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_FALSE(s.meshes[1].animation);
    EXPECT_NEAR(centroid(s.meshes[1]).x, 0.0, 1e-12);  // the box node has no translation
    EXPECT_FALSE(sceneMoves(s));
}

TEST(GltfAnimation, TheBoxSlidesAndTheFloorStays) {
    Scene s = loadScene(
        writeScene("slide", "sliding_box.gltf", R"(, "sequence": {"frames": 16, "fps": 30})"));
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_FALSE(s.meshes[0].animation);
    ASSERT_TRUE(s.meshes[1].animation);
    EXPECT_TRUE(sceneMoves(s));
    EXPECT_NEAR(centroid(s.meshes[1]).x, -2.0, 1e-12);  // frame 0 is the pose at t = 0
    const double t = sequenceTime(*s.sequence, 8);
    Scene posed = sceneAtTime(s, t);
    EXPECT_NEAR(centroid(posed.meshes[1]).x, -2.0 + 4.0 * t / 0.5, 1e-12);
    EXPECT_EQ(posed.meshes[0].wsPositions, s.meshes[0].wsPositions);
    EXPECT_FALSE(posed.sequence);
    EXPECT_FALSE(sceneMoves(posed));
    EXPECT_NE(posed.contentHash, s.contentHash);
    EXPECT_NE(posed.contentHash, sceneAtTime(s, sequenceTime(*s.sequence, 9)).contentHash);
    EXPECT_NEAR(posed.wsBounds.hi.y, 1.0, 1e-12);
    // Past the last key the box stays where the last key put it.
    EXPECT_NEAR(centroid(sceneAtTime(s, 10.0).meshes[1]).x, 2.0, 1e-12);
    // The motion from frame 8 to frame 9 carries the posed box onto the next pose.
    const double t9 = sequenceTime(*s.sequence, 9);
    const glm::dmat4 motion = meshMotion(s, 1, t, t9);
    const glm::dvec3 moved(motion * glm::dvec4(posed.meshes[1].wsPositions[0], 1.0));
    const glm::dvec3 next = sceneAtTime(s, t9).meshes[1].wsPositions[0];
    EXPECT_NEAR(glm::length(moved - next), 0.0, 1e-12);
    EXPECT_EQ(meshMotion(s, 0, t, t9), glm::dmat4(1.0));
}

// An animated parent moves its child: "arm" turns 0 -> 90 degrees about y over 1 s, "hand" sits
// at (1, 0, 0) under it, so at t = 0.5 the hand is at (cos 45, 0, -sin 45).
TEST(GltfAnimation, AnAnimatedParentMovesItsChild) {
    Scene s =
        loadScene(writeScene("chain", "chain.gltf", R"(, "sequence": {"frames": 4, "fps": 2})"));
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_TRUE(s.meshes[0].animation);
    const glm::dvec3 c0 = centroid(s.meshes[0]);
    const glm::dvec3 c = centroid(sceneAtTime(s, 0.5).meshes[0]);
    const double r = std::sqrt(c0.x * c0.x + c0.z * c0.z);
    const double a = std::numbers::pi / 4.0;
    // The rotation about y turns the centroid (r, cz) by 45 degrees: x' = x cos + z sin,
    // z' = -x sin + z cos.
    // The keys are float32 (the 90-degree quaternion's sqrt(1/2) is rounded): 1e-7 of a turn.
    const double tol = 1e-7;
    EXPECT_NEAR(c.x, c0.x * std::cos(a) + c0.z * std::sin(a), tol);
    EXPECT_NEAR(c.z, -c0.x * std::sin(a) + c0.z * std::cos(a), tol);
    EXPECT_NEAR(std::sqrt(c.x * c.x + c.z * c.z), r, 1e-12);  // a rotation keeps the radius
    const glm::dvec3 c1 = centroid(sceneAtTime(s, 1.0).meshes[0]);
    EXPECT_NEAR(c1.x, c0.z, tol);
    EXPECT_NEAR(c1.z, -c0.x, tol);
}

TEST(GltfAnimation, TheClipNamedPlaysAndAnUnknownOneIsAnError) {
    Scene s =
        loadScene(writeScene("named", "sliding_box.gltf",
                             R"(, "sequence": {"frames": 2, "fps": 30, "animation": "slide"})"));
    EXPECT_TRUE(s.meshes[1].animation);
    try {
        loadScene(writeScene("unknown", "sliding_box.gltf",
                             R"(, "sequence": {"frames": 2, "fps": 30, "animation": "jump"})"));
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("sequence.animation"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("slide"), std::string::npos) << e.what();
    }
}

// The keys of the clips that play are bounded (the sliding box's clip has 2).
TEST(GltfAnimation, KeysBeyondTheLimitAreAnError) {
    const fs::path path =
        writeScene("limit", "sliding_box.gltf", R"(, "sequence": {"frames": 2, "fps": 30})");
    LoadLimits limits;
    limits.maxAnimationKeys = 2;
    EXPECT_NO_THROW(loadScene(path, limits));
    limits.maxAnimationKeys = 1;
    try {
        loadScene(path, limits);
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("over maxAnimationKeys (1)"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace so
