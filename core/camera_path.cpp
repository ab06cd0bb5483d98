#include "core/camera_path.h"

#include <algorithm>
#include <cstdio>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace so {

namespace {

// One keyframe's pose with the base camera's defaults filled in.
struct Pose {
    glm::dvec3 wsEye, wsTarget, wsUp;
    double vfovDeg;
};

Pose poseOf(const CameraKeyframe& k, const CameraDesc& base) {
    return {k.wsEye, k.wsTarget, k.wsUp.value_or(base.wsUp), k.vfovDeg.value_or(base.vfovDeg)};
}

// Cubic Hermite between p1 (at t1) and p2 (at t2), tangents m1, m2 per unit t.
glm::dvec3 hermite(const glm::dvec3& p1, const glm::dvec3& m1, const glm::dvec3& p2,
                   const glm::dvec3& m2, double t1, double t2, double s) {
    const double dt = t2 - t1;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
    const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    return h00 * p1 + h10 * dt * m1 + h01 * p2 + h11 * dt * m2;
}

// Catmull-Rom tangent at keyframe i for one of the pose's vectors: the neighbours' difference over
// their t (one-sided at the ends), so unevenly spaced keys keep a smooth speed.
template <typename Get>
glm::dvec3 tangent(const std::vector<CameraKeyframe>& keys, const std::vector<Pose>& poses,
                   size_t i, Get get) {
    const size_t lo = i == 0 ? 0 : i - 1, hi = std::min(i + 1, keys.size() - 1);
    return (get(poses[hi]) - get(poses[lo])) / (keys[hi].t - keys[lo].t);
}

void checkSample(const CameraDesc& c, const CameraPath& path, double t) {
    const glm::dvec3 forward = c.wsTarget - c.wsEye;
    const char* why = nullptr;
    if (!(glm::length(forward) > 0.0))
        why = "eye reaches target";
    else if (!(glm::length(glm::cross(glm::normalize(forward), c.wsUp)) >
               1e-9 * glm::length(c.wsUp)))
        why = "up is parallel to the viewing direction";
    if (!why) return;
    char text[160];
    std::snprintf(text, sizeof text, "at t = %.6g the interpolated camera is degenerate: %s", t,
                  why);
    throwInputError(path.file, "camera_path", text);
}

}  // namespace

CameraDesc cameraAt(const CameraPath& path, const CameraDesc& base, double t) {
    const std::vector<CameraKeyframe>& keys = path.keyframes;
    std::vector<Pose> poses;
    for (const CameraKeyframe& k : keys) poses.push_back(poseOf(k, base));
    t = std::clamp(t, keys.front().t, keys.back().t);
    // The segment [keys[i].t, keys[i+1].t] holding t.
    size_t i = 0;
    while (i + 2 < keys.size() && t >= keys[i + 1].t) ++i;
    const double s = (t - keys[i].t) / (keys[i + 1].t - keys[i].t);
    const Pose &a = poses[i], &b = poses[i + 1];
    CameraDesc c = base;
    c.vfovDeg = a.vfovDeg + s * (b.vfovDeg - a.vfovDeg);
    // The end points exactly, whatever the arithmetic would round to.
    if (s == 0.0 || s == 1.0) {
        const Pose& p = s == 0.0 ? a : b;
        c.wsEye = p.wsEye, c.wsTarget = p.wsTarget, c.wsUp = p.wsUp, c.vfovDeg = p.vfovDeg;
        return c;
    }
    if (path.interpolation == PathInterpolation::Linear) {
        c.wsEye = a.wsEye + s * (b.wsEye - a.wsEye);
        c.wsTarget = a.wsTarget + s * (b.wsTarget - a.wsTarget);
        c.wsUp = a.wsUp + s * (b.wsUp - a.wsUp);
        return c;
    }
    const double t1 = keys[i].t, t2 = keys[i + 1].t;
    auto spline = [&](auto get) {
        return hermite(get(a), tangent(keys, poses, i, get), get(b),
                       tangent(keys, poses, i + 1, get), t1, t2, s);
    };
    c.wsEye = spline([](const Pose& p) { return p.wsEye; });
    c.wsTarget = spline([](const Pose& p) { return p.wsTarget; });
    c.wsUp = spline([](const Pose& p) { return p.wsUp; });
    return c;
}

std::vector<CameraDesc> sampleCameraPath(const CameraPath& path, const CameraDesc& base,
                                         int frames) {
    std::vector<CameraDesc> out;
    if (path.keyframes.size() < 2 || frames < 2) return out;
    const double t0 = path.keyframes.front().t, tN = path.keyframes.back().t;
    for (int f = 0; f < frames; ++f) {
        // The last frame at tN exactly, not at t0 + (tN - t0) rounded.
        const double t = f == frames - 1 ? tN : t0 + (tN - t0) * double(f) / double(frames - 1);
        out.push_back(cameraAt(path, base, t));
        checkSample(out.back(), path, t);
    }
    return out;
}

}  // namespace so
