#include "raster_compare/gl/shadow_maps/light_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "raster_compare/gl/lights/raster_light_kind.h"

namespace so {

namespace {

glm::dvec3 anyUp(const glm::dvec3& forward) {
    return std::fabs(forward.y) < 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
}

// The corners of a box.
std::array<glm::dvec3, 8> corners(const Bounds3d& b) {
    std::array<glm::dvec3, 8> c;
    for (int k = 0; k < 8; ++k)
        c[size_t(k)] = glm::dvec3((k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y,
                                  (k & 4) ? b.hi.z : b.lo.z);
    return c;
}

// Near and far planes around a point that enclose the bounds, for a square frustum of half-angle
// `halfFovRad`: far reaches the farthest corner; near lies in front of every point of the box
// inside the frustum (a little more), but at least far / 1e4 for depth precision. A plane cuts at
// view depth, not distance: a point at distance d inside the frustum has depth at least
// d cos(alpha), alpha the angle of the frustum's corner ray (tan alpha = sqrt(2) tan(half-angle)).
// With the distance alone the tops of the objects nearest a tilted spot fell in front of the near
// plane and out of the map (found by tests/cli/view_test.cpp).
void enclose(const glm::dvec3& eye, const Bounds3d& b, double halfFovRad, double& near,
             double& far) {
    far = 0.0;
    for (const glm::dvec3& c : corners(b)) far = std::max(far, glm::length(c - eye));
    far = far * 1.01 + 1e-6;
    const glm::dvec3 nearest = glm::clamp(eye, b.lo, b.hi);
    const double t = std::tan(halfFovRad);
    const double cosCorner = 1.0 / std::sqrt(1.0 + 2.0 * t * t);
    near = std::max(0.99 * glm::length(nearest - eye) * cosCorner, far * 1e-4);
}

// Points in a view's frame: their bounds.
template <size_t N>
void viewBounds(const glm::dmat4& viewFromLocal, const std::array<glm::dvec3, N>& points,
                glm::dvec3& lo, glm::dvec3& hi) {
    lo = glm::dvec3(1e300);
    hi = glm::dvec3(-1e300);
    for (const glm::dvec3& p : points) {
        const glm::dvec3 v = glm::dvec3(viewFromLocal * glm::dvec4(p, 1.0));
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
}

// A directional light's view (looking along its direction at the bounds' centre) and the near
// and far planes that enclose the bounds (sceneLo, sceneHi: the bounds in that view).
void directionalView(LightCamera& lc, const Bounds3d& b, glm::dvec3& sceneLo, glm::dvec3& sceneHi) {
    lc.kind = LightCamera::Kind::Ortho;
    const glm::dvec3 centre = b.center();
    const double radius = 0.5 * b.extent() + 1e-6;
    const glm::dvec3 eye = centre - lc.lsDirection * (2.0 * radius);
    lc.viewFromLocal[0] = glm::lookAtRH(eye, centre, anyUp(lc.lsDirection));
    viewBounds(lc.viewFromLocal[0], corners(b), sceneLo, sceneHi);
    lc.near = std::max(0.0, -sceneHi.z - 0.01 * radius);
    lc.far = -sceneLo.z + 0.01 * radius;
}

}  // namespace

LightCamera fitLightCamera(const Light& light, const LocalFrame& frame, const Bounds3d& b,
                           int resolution, const Bounds3d* lsReceivers) {
    LightCamera lc;
    lc.lsPosition = frame.lsFromWs(light.wsPosition);
    lc.lsDirection = glm::normalize(light.wsDirection);
    lc.lsEmitNormal = light.wsEmitNormal();  // the local frame only scales and translates
    const LightCamera::Kind kind = rasterLightKind(light.type).cameraKind();
    if (kind == LightCamera::Kind::Ortho) {
        glm::dvec3 lo, hi;
        directionalView(lc, b, lo, hi);
        if (lsReceivers && !lsReceivers->empty()) {
            glm::dvec3 rlo, rhi;
            viewBounds(lc.viewFromLocal[0], corners(*lsReceivers), rlo, rhi);
            lo.x = rlo.x, lo.y = rlo.y, hi.x = rhi.x, hi.y = rhi.y;
        }
        // Square texels.
        const double half = 0.5 * std::max(hi.x - lo.x, hi.y - lo.y) * 1.01;
        const double cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y);
        lc.clipFromView[0] =
            glm::orthoRH_ZO(cx - half, cx + half, cy - half, cy + half, lc.near, lc.far);
        lc.texelScale = 2.0 * half / resolution;
        return lc;
    }
    if (kind == LightCamera::Kind::Perspective) {
        lc.kind = LightCamera::Kind::Perspective;
        lc.fovYDeg = std::min(170.0, 2.0 * light.outerConeDeg * 1.02);
        enclose(lc.lsPosition, b, 0.5 * lc.fovYDeg * std::numbers::pi / 180.0, lc.near, lc.far);
        lc.cosOuter = std::cos(light.outerConeDeg * std::numbers::pi / 180.0);
        lc.viewFromLocal[0] =
            glm::lookAtRH(lc.lsPosition, lc.lsPosition + lc.lsDirection, anyUp(lc.lsDirection));
        const double fov = lc.fovYDeg * std::numbers::pi / 180.0;
        lc.clipFromView[0] = glm::perspectiveRH_ZO(fov, 1.0, lc.near, lc.far);
        lc.texelScale = 2.0 * std::tan(0.5 * fov) / resolution;
        return lc;
    }
    // Point lights, and area lights from their centre: the GL cube-map face order and orientation.
    lc.kind = LightCamera::Kind::Cube;
    lc.faces = 6;
    lc.fovYDeg = 90.0;
    enclose(lc.lsPosition, b, std::numbers::pi / 4, lc.near, lc.far);
    const glm::dvec3 dirs[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    const glm::dvec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                               {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    for (int f = 0; f < 6; ++f) {
        lc.viewFromLocal[size_t(f)] = glm::lookAtRH(lc.lsPosition, lc.lsPosition + dirs[f], ups[f]);
        lc.clipFromView[size_t(f)] =
            glm::perspectiveRH_ZO(std::numbers::pi / 2, 1.0, lc.near, lc.far);
    }
    lc.texelScale = 2.0 / resolution;
    return lc;
}

std::vector<LightSpaceFace> lightSpaceFaces(const Light& light, const Bounds3d& wsSceneBounds,
                                            const Bounds3d* lsReceivers) {
    const LocalFrame frame = LocalFrame::fit(wsSceneBounds);
    Bounds3d lsBounds;
    if (!wsSceneBounds.empty()) {
        lsBounds.extend(frame.lsFromWs(wsSceneBounds.lo));
        lsBounds.extend(frame.lsFromWs(wsSceneBounds.hi));
    }
    // The resolution only sets texelScale, which is not handed out.
    const LightCamera lc = fitLightCamera(light, frame, lsBounds, 2048, lsReceivers);
    // localFromWorld = S T(-centre) with S = 2^-exponent: a lookAt in local space is R (l - eye),
    // so S^-1 viewFromLocal localFromWorld = R (w - wsEye) is rigid, and the projection takes
    // S back: clipFromView S.
    const double toLocal = std::ldexp(1.0, -frame.exponent);
    const glm::dmat4 localFromWorld =
        glm::translate(glm::scale(glm::dmat4(1.0), glm::dvec3(toLocal)), -frame.wsCenter);
    const glm::dmat4 scaleToLocal = glm::scale(glm::dmat4(1.0), glm::dvec3(toLocal));
    const glm::dmat4 scaleToWorld = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0 / toLocal));
    static const char* const kCubeFaces[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    std::vector<LightSpaceFace> faces;
    for (int f = 0; f < lc.faces; ++f)
        faces.push_back({lc.kind == LightCamera::Kind::Cube ? kCubeFaces[f] : "map",
                         scaleToWorld * lc.viewFromLocal[size_t(f)] * localFromWorld,
                         lc.clipFromView[size_t(f)] * scaleToLocal});
    return faces;
}

double practicalSplit(double near, double far, int i, int n, double lambda) {
    const double f = double(i) / double(n);
    return lambda * near * std::pow(far / near, f) + (1.0 - lambda) * (near + (far - near) * f);
}

void cascadeRange(const CascadeView& view, double& lsNear, double& lsFar) {
    const double far = std::max(view.lsFarthest, 1e-30);
    lsFar = std::exp2(std::ceil(std::log2(far)));
    lsNear = std::exp2(std::floor(std::log2(std::max(view.lsNearest, far * 0x1p-12))));
}

namespace {

// The corners of the camera frustum's slice between view depths d0 and d1.
std::array<glm::dvec3, 8> sliceCorners(const CascadeView& v, double d0, double d1) {
    std::array<glm::dvec3, 8> c;
    for (int k = 0; k < 8; ++k) {
        const double d = (k & 4) ? d1 : d0;
        const double sx = (k & 1) ? 1.0 : -1.0, sy = (k & 2) ? 1.0 : -1.0;
        c[size_t(k)] = v.lsEye + d * (v.forward + sx * v.tanHalfVfov * v.aspect * v.right +
                                      sy * v.tanHalfVfov * v.up);
    }
    return c;
}

// One cascade's square window in the light's view (slice: its frustum corners between view
// depths d0 and d1): its centre and half side.
void fitSlice(const LightCamera& lc, const CascadeView& v, double d0, double d1, bool snap,
              int resolution, double& cx, double& cy, double& half) {
    if (!snap) {
        glm::dvec3 lo, hi;
        viewBounds(lc.viewFromLocal[0], sliceCorners(v, d0, d1), lo, hi);
        half = 0.5 * std::max(hi.x - lo.x, hi.y - lo.y) * 1.01;
        cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y);
        return;
    }
    // The sphere about the slice's centroid (on the view axis, at the mean depth): its radius is
    // computed from the split depths and the field of view alone, never from the camera's pose,
    // so the texel size is the same bit for bit in every frame; its centre moves in whole texels,
    // so every texel edge stays where it was.
    const double zc = 0.5 * (d0 + d1), t = v.tanHalfVfov;
    auto cornerDistance = [&](double d) {
        const glm::dvec3 c(d * t * v.aspect, d * t, d - zc);
        return glm::length(c);
    };
    // Margin: the snapped centre is up to a texel off the sphere's (texel = 2 half / resolution).
    half = std::max(cornerDistance(d0), cornerDistance(d1)) * 1.01 * resolution / (resolution - 2);
    const double texel = 2.0 * half / resolution;
    const glm::dvec3 centre = v.lsEye + zc * v.forward;
    const glm::dvec3 c = glm::dvec3(lc.viewFromLocal[0] * glm::dvec4(centre, 1.0));
    cx = std::floor(c.x / texel) * texel;
    cy = std::floor(c.y / texel) * texel;
}

}  // namespace

LightCamera fitCascades(const Light& light, const Bounds3d& lsBounds, int resolution,
                        const CascadeView& view, const CascadeSettings& settings) {
    LightCamera lc;
    lc.lsDirection = glm::normalize(light.wsDirection);
    glm::dvec3 sceneLo, sceneHi;
    directionalView(lc, lsBounds, sceneLo, sceneHi);
    lc.kind = LightCamera::Kind::Cascades;
    lc.faces = settings.count;
    double lsNear = 0.0, lsFar = 0.0;
    cascadeRange(view, lsNear, lsFar);
    for (int i = 0; i <= settings.count; ++i)
        lc.lsSplits[size_t(i)] = practicalSplit(lsNear, lsFar, i, settings.count, settings.lambda);
    for (int i = 0; i < settings.count; ++i) {
        double cx = 0.0, cy = 0.0, half = 0.0;
        fitSlice(lc, view, lc.lsSplits[size_t(i)], lc.lsSplits[size_t(i) + 1], settings.snap,
                 resolution, cx, cy, half);
        lc.viewFromLocal[size_t(i)] = lc.viewFromLocal[0];
        lc.clipFromView[size_t(i)] =
            glm::orthoRH_ZO(cx - half, cx + half, cy - half, cy + half, lc.near, lc.far);
        lc.cascadeTexel[size_t(i)] = 2.0 * half / resolution;
    }
    lc.texelScale = lc.cascadeTexel[0];
    return lc;
}

// Cascades are orthographic maps to the techniques' lookups.
std::string lightCameraDefines(const LightCamera& cam) {
    switch (cam.kind) {
        case LightCamera::Kind::Cube:
            return "#define LIGHT_CUBE\n";
        case LightCamera::Kind::Ortho:
            return "#define LIGHT_ORTHO\n";
        case LightCamera::Kind::Cascades:
            return "#define LIGHT_ORTHO\n#define CASCADES " + std::to_string(cam.faces) + "\n";
        default:
            return "#define LIGHT_SPOT\n";
    }
}

std::string lightCameraDefines(const Light& light) {
    LightCamera cam;
    cam.kind = rasterLightKind(light.type).cameraKind();
    return lightCameraDefines(cam);
}

double lightWidth(const Light& light) {
    const RasterAreaLightKind* kind = rasterAreaLightKind(light.type);
    return kind ? kind->width(light) : 0.0;
}

}  // namespace so
