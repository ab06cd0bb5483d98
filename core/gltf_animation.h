// glTF 2.0 node animation (spec 3.11 and Appendix C) as the scene keeps it: rigid motion of the
// drawn primitives, sampled on the sequence's clock in seconds (docs/scene-format.md#animations).
// The loader (gltf_loader.cpp, gltf_animation_load.cpp) fills these only in a scene with a
// `sequence`; core/scene_pose.h poses a scene with them.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace so {

enum class AnimationInterpolation { Step, Linear, CubicSpline };
enum class AnimatedProperty { Translation, Rotation, Scale };

// One sampler driving one property of one node. `times` in seconds, at least 1, strictly
// increasing. `values` holds one value a key (three for CubicSpline: in-tangent, value,
// out-tangent), xyz in x, y, z for translation and scale, a quaternion (x, y, z, w) for rotation.
struct AnimationTrack {
    AnimatedProperty property = AnimatedProperty::Translation;
    AnimationInterpolation interpolation = AnimationInterpolation::Linear;
    std::vector<double> times;
    std::vector<glm::dvec4> values;

    // The value at `t`: the first key's value before the first key, the last's after the last;
    // between keys STEP holds the earlier key, LINEAR lerps (rotation: slerp along the shortest
    // arc), CUBICSPLINE is the Hermite spline with tangents scaled by the key interval. A
    // rotation comes back as a unit quaternion.
    glm::dvec4 sample(double t) const;
};

// A node's local transform over time: the file's TRS (or matrix, for a node no track targets),
// each property a track targets replaced by the track's value at t.
struct AnimatedNode {
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
    glm::dmat4 restLocal{1.0};           // the file's own local transform (matrix or T * R * S)
    std::vector<AnimationTrack> tracks;  // at most one per property
    glm::dmat4 localAt(double t) const;  // restLocal when no track plays
};

// The motion of one drawn primitive: world(t) = wsFromFile * chain[0](t) * ... * chain.back()(t),
// the chain running from a root of the glTF scene down to the primitive's node. Only primitives
// under at least one animated node have one (MeshPrimitive::animation).
struct MeshAnimation {
    glm::dmat4 wsFromFile{1.0};
    std::vector<std::shared_ptr<const AnimatedNode>> chain;
    // The primitive's POSITIONs as the file stores them (the node's space): wsPositions at t are
    // worldAt(t) applied to these, so a pose that scales to zero loses nothing.
    std::vector<glm::dvec3> lsPositions;
    glm::dmat4 worldAt(double t) const;
};

// Spherical interpolation of unit quaternions (x, y, z, w) along the shortest arc, at u in [0, 1].
glm::dvec4 slerpShortest(const glm::dvec4& a, const glm::dvec4& b, double u);

}  // namespace so
