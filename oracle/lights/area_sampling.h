// What the area light kinds (area_light_kind.h) share to sample their lights: the branch-free
// trigonometry of the samplers' loops, the batch's points, and the finishing step that turns
// points into directions and weights (area_light.cpp). Internal to the oracle.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/vec3.hpp>

#include "oracle/area_light.h"

namespace so {

// The samplers' loops, once for AVX2 (eight lanes at a time) and once for any x86-64, chosen at
// run time. Neither enables fused multiply-add, and both round every operation the same IEEE way,
// so the samples are the same bits on any CPU.
#define SO_SAMPLER_CLONES __attribute__((target_clones("avx2", "default")))

// sin and cos on [-pi/4, pi/4] by their Taylor polynomials (errors below 1e-8, under float's
// resolution): unlike std::sin/cos these vectorise, and the samplers call them for every sample.
inline void sincosQuarterPi(float x, float& s, float& c) {
    const float x2 = x * x;
    s = x *
        (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
    c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
}

// sin and cos of 2 pi v for v in [0, 1): reduced to a quarter turn around pi/4 + q pi/2.
inline void sincos2Pi(float v, float& s, float& c) {
    const float q = float(int(v * 4.0f));  // v >= 0: truncation is floor, and vectorises
    const float x =
        2.0f * std::numbers::pi_v<float> * (v - 0.25f * q) - std::numbers::pi_v<float> / 4;
    float sx, cx;
    sincosQuarterPi(x, sx, cx);
    const float h = std::numbers::sqrt2_v<float> / 2;
    const float c0 = h * (cx - sx), s0 = h * (sx + cx);  // angle pi/4 + x
    c = q == 0.0f ? c0 : q == 1.0f ? -s0 : q == 2.0f ? -c0 : s0;
    s = q == 0.0f ? s0 : q == 1.0f ? c0 : q == 2.0f ? -s0 : -c0;
}

// The horizon cuts a circle of directions or points, parametrised by an angle t about the
// direction towards the receiver's normal, where toward + across cos t > 0 (across >= 0): the
// half-angle of the arc above it, pi when all of the circle is, about 0 when none is. Never below
// the true arc: a sample past the horizon has weight 0, so the estimate stays unbiased, while an
// arc too short would miss part of the light. Branch-free, so the samplers' loops vectorise.
inline float arcAboveHorizon(float toward, float across) {
    const float x = std::clamp(-toward / std::max(across, 1e-30f), -1.0f, 1.0f);
    return toward - across >= 0.0f ? std::numbers::pi_v<float> : acosUpperBound(x);
}

// sin and cos of t = (2 v - 1) halfAngle for v in [0, 1): uniform over the arc.
inline void sincosOnArc(float v, float halfAngle, float& s, float& c) {
    float turn = (2.0f * v - 1.0f) * halfAngle * (0.5f / std::numbers::pi_v<float>);
    turn = turn < 0.0f ? turn + 1.0f : turn;
    turn = turn >= 1.0f ? 0.0f : turn;
    sincos2Pi(turn, s, c);
}

// Points on the light, one branch-free loop per shape; `share` is the weight factor of a sample
// whose circle the horizon cuts (1 elsewhere).
struct LightPoints {
    float x[16], y[16], z[16];
    float share[16];
};

// Directions, segment lengths and weights G / pdf from the points (`share` set by the caller).
void finishAreaBatch(const AreaLight& light, const AreaPixel& px, const LightPoints& q, int count,
                     float margin, AreaBatch& b);

// Points uniform by area over a fan of triangles (3 points each, `fan`) with cumulative area shares
// `cdf`: u picks the triangle, the rest of u and v place the point in it (the rect clipped to the
// horizon, the polygon).
void fanAreaPoints(const glm::vec3* fan, const float* cdf, int triangles, const float* su,
                   const float* sv, LightPoints& q);

// classifyAreaPixel for a one-sided emitter (rect, disk, polygon): p must be in front of its
// plane, and its highest point above p's tangent plane by `top` (`reach`: the distance that
// margin's rounding scales with). Ties decided exactly with `ties` (area_light.h).
AreaSkip classifyOneSidedPixel(const AreaLight& light, const glm::dvec3& p, const PixelTies* ties,
                               double top, double reach);

}  // namespace so
