#include "core/gltf_animation.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace so {
namespace {

glm::dvec4 normalizedQuat(const glm::dvec4& q) {
    const double len = glm::length(q);
    return len > 0.0 ? q / len : glm::dvec4(0.0, 0.0, 0.0, 1.0);
}

// The Hermite spline of glTF Appendix C between keys k and k + 1 at s in [0, 1]: values are the
// middle of each triple, tangents are scaled by the key interval `dt`.
glm::dvec4 hermite(const std::vector<glm::dvec4>& v, size_t k, double s, double dt) {
    const glm::dvec4& p0 = v[3 * k + 1];
    const glm::dvec4& out0 = v[3 * k + 2];
    const glm::dvec4& in1 = v[3 * (k + 1)];
    const glm::dvec4& p1 = v[3 * (k + 1) + 1];
    const double s2 = s * s, s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * p0 + dt * (s3 - 2.0 * s2 + s) * out0 +
           (-2.0 * s3 + 3.0 * s2) * p1 + dt * (s3 - s2) * in1;
}

}  // namespace

glm::dvec4 slerpShortest(const glm::dvec4& a, const glm::dvec4& bIn, double u) {
    glm::dvec4 b = bIn;
    double cosTheta = glm::dot(a, b);
    if (cosTheta < 0.0) {  // q and -q are the same rotation: take the shorter way round
        b = -b;
        cosTheta = -cosTheta;
    }
    // Nearly parallel: the sine below vanishes, and the lerp is exact to rounding there.
    if (cosTheta > 1.0 - 1e-12) return normalizedQuat(a + u * (b - a));
    const double theta = std::acos(std::min(cosTheta, 1.0));
    const double sinTheta = std::sin(theta);
    return normalizedQuat((std::sin((1.0 - u) * theta) / sinTheta) * a +
                          (std::sin(u * theta) / sinTheta) * b);
}

glm::dvec4 AnimationTrack::sample(double t) const {
    const bool cubic = interpolation == AnimationInterpolation::CubicSpline;
    const size_t keys = times.size();
    auto value = [&](size_t k) { return values[cubic ? 3 * k + 1 : k]; };
    glm::dvec4 result;
    if (!(t > times.front())) {
        result = value(0);
    } else if (!(t < times.back())) {
        result = value(keys - 1);
    } else {
        // times[k] <= t < times[k + 1]
        const size_t k =
            size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
        const double dt = times[k + 1] - times[k];
        const double s = (t - times[k]) / dt;
        if (interpolation == AnimationInterpolation::Step)
            result = value(k);
        else if (cubic)
            result = hermite(values, k, s, dt);
        else if (property == AnimatedProperty::Rotation)
            result = slerpShortest(value(k), value(k + 1), s);
        else
            result = value(k) + s * (value(k + 1) - value(k));
    }
    return property == AnimatedProperty::Rotation ? normalizedQuat(result) : result;
}

glm::dmat4 AnimatedNode::localAt(double t) const {
    if (tracks.empty()) return restLocal;
    glm::dvec3 tr = translation, sc = scale;
    glm::dquat rot = rotation;
    for (const AnimationTrack& track : tracks) {
        const glm::dvec4 v = track.sample(t);
        if (track.property == AnimatedProperty::Translation) tr = glm::dvec3(v);
        if (track.property == AnimatedProperty::Scale) sc = glm::dvec3(v);
        if (track.property == AnimatedProperty::Rotation) rot = glm::dquat(v.w, v.x, v.y, v.z);
    }
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), tr) * glm::mat4_cast(rot);
    return glm::scale(m, sc);
}

glm::dmat4 MeshAnimation::worldAt(double t) const {
    glm::dmat4 world = wsFromFile;
    for (const auto& node : chain) world = world * node->localAt(t);
    return world;
}

}  // namespace so
