#include "oracle/area_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "oracle/offset.h"
#include "oracle/sobol.h"

namespace so {

AreaLight makeAreaLight(const Light& light, const LocalFrame& frame) {
    AreaLight a;
    a.type = light.type;
    a.dCenter = frame.lsFromWs(light.wsPosition);
    const double s = frame.lsLength(1.0);  // the frame scales lengths by a power of two
    a.dU = light.wsU * s;
    a.dV = light.wsV * s;
    a.dEmitNormal = light.wsEmitNormal();
    a.dRadius = light.radius * s;
    a.lsCenter = glm::vec3(a.dCenter);
    a.lsU = glm::vec3(a.dU);
    a.lsV = glm::vec3(a.dV);
    a.lsEmitNormal = glm::vec3(a.dEmitNormal);
    a.lsRadius = float(a.dRadius);
    if (light.type == LightType::Disk) {
        glm::dvec3 m = a.dEmitNormal;
        glm::dvec3 helper = std::fabs(m.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        glm::dvec3 e1 = glm::normalize(glm::cross(helper, m));
        a.lsE1 = glm::vec3(e1);
        a.lsE2 = glm::vec3(glm::cross(m, e1));
    }
    // The end margin of the light's farthest point from the frame's origin.
    const double extent =
        light.type == LightType::Rect ? 0.5 * (glm::length(a.dU) + glm::length(a.dV)) : a.dRadius;
    const glm::dvec3 far = glm::abs(a.dCenter) + glm::dvec3(extent);
    a.lsEndMargin = offsetMargin(glm::vec3(far));
    return a;
}

AreaSkip classifyAreaPixel(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n) {
    const glm::dvec3 c = light.dCenter;
    switch (light.type) {
        case LightType::Rect: {
            if (!(glm::dot(light.dEmitNormal, p - c) > 0.0)) return AreaSkip::BehindLight;
            bool above = false;
            for (int k = 0; k < 4; ++k) {
                glm::dvec3 corner =
                    c + ((k & 1) ? 0.5 : -0.5) * light.dU + ((k & 2) ? 0.5 : -0.5) * light.dV;
                above |= glm::dot(n, corner - p) > 0.0;
            }
            return above ? AreaSkip::None : AreaSkip::BelowHorizon;
        }
        case LightType::Disk: {
            if (!(glm::dot(light.dEmitNormal, p - c) > 0.0)) return AreaSkip::BehindLight;
            // The disk's highest point above p's tangent plane.
            const double nm = glm::dot(n, light.dEmitNormal);
            const double top =
                glm::dot(n, c - p) + light.dRadius * std::sqrt(std::max(0.0, 1.0 - nm * nm));
            return top > 0.0 ? AreaSkip::None : AreaSkip::BelowHorizon;
        }
        case LightType::Sphere: {
            const glm::dvec3 d = c - p;
            if (glm::dot(d, d) <= light.dRadius * light.dRadius) return AreaSkip::InsideLight;
            return glm::dot(n, d) + light.dRadius > 0.0 ? AreaSkip::None : AreaSkip::BelowHorizon;
        }
        default:
            return AreaSkip::None;
    }
}

AreaPixel prepareAreaPixel(const AreaLight& light, const glm::vec3& p, const glm::vec3& n) {
    AreaPixel px;
    px.p = p;
    px.n = n;
    if (light.type == LightType::Sphere) {
        const glm::dvec3 d = glm::dvec3(light.lsCenter) - glm::dvec3(p);
        const double dist = glm::length(d);
        const glm::dvec3 wc = d / dist;
        const double sin2 =
            std::min(1.0, (double(light.lsRadius) * light.lsRadius) / (dist * dist));
        const double cosMax = std::sqrt(1.0 - sin2);
        glm::dvec3 helper = std::fabs(wc.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        glm::dvec3 t1 = glm::normalize(glm::cross(helper, wc));
        px.wc = glm::vec3(wc);
        px.t1 = glm::vec3(t1);
        px.t2 = glm::vec3(glm::cross(wc, t1));
        px.dist = float(dist);
        // 1 - cos(theta_max) without cancellation for small, distant spheres.
        px.oneMinusCosMax = float(sin2 / (1.0 + cosMax));
        px.radius2 = light.lsRadius * light.lsRadius;
    }
    return px;
}

void sampleAreaBatch(const AreaLight& light, const AreaPixel& px, uint32_t seed, uint32_t first,
                     int count, AreaBatch& b) {
    float su[16], sv[16];
    for (int k = 0; k < 16; ++k) sobol2D(first + uint32_t(k), seed, su[k], sv[k]);
    const float margin = 2.0f * light.lsEndMargin;
    if (light.type == LightType::Sphere) {
        for (int k = 0; k < 16; ++k) {
            const float cosT = 1.0f - su[k] * px.oneMinusCosMax;
            const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
            const float phi = 2.0f * std::numbers::pi_v<float> * sv[k];
            const float cx = std::cos(phi) * sinT, cy = std::sin(phi) * sinT;
            const glm::vec3 d = cx * px.t1 + cy * px.t2 + cosT * px.wc;
            // Distance to the near side of the sphere along d.
            const float b2 = px.dist * cosT;
            const float disc = std::max(0.0f, px.radius2 - px.dist * px.dist * sinT * sinT);
            const float t = b2 - std::sqrt(disc);
            const float cosP = glm::dot(px.n, d);
            b.dirX[k] = d.x;
            b.dirY[k] = d.y;
            b.dirZ[k] = d.z;
            b.tfar[k] = std::max(0.0f, t - margin);
            b.weight[k] = (k < count && cosP > 0.0f) ? cosP : 0.0f;
        }
        return;
    }
    for (int k = 0; k < 16; ++k) {
        glm::vec3 y;
        if (light.type == LightType::Rect) {
            y = light.lsCenter + (su[k] - 0.5f) * light.lsU + (sv[k] - 0.5f) * light.lsV;
        } else {
            // Shirley-Chiu concentric map: area-preserving and keeps the strata compact.
            const float a = 2.0f * su[k] - 1.0f, c = 2.0f * sv[k] - 1.0f;
            const bool first4 = std::fabs(a) > std::fabs(c);
            const float r = first4 ? a : c;
            const float theta =
                first4 ? (std::numbers::pi_v<float> / 4) * (c / (a == 0.0f ? 1.0f : a))
                       : (std::numbers::pi_v<float> / 2) -
                             (std::numbers::pi_v<float> / 4) * (a / (c == 0.0f ? 1.0f : c));
            y = light.lsCenter +
                light.lsRadius * r * (std::cos(theta) * light.lsE1 + std::sin(theta) * light.lsE2);
        }
        const glm::vec3 d = y - px.p;
        const float r2 = glm::dot(d, d);
        const float dist = std::sqrt(r2);
        const glm::vec3 w = d * (1.0f / dist);
        const float cosP = glm::dot(px.n, w);
        const float cosY = -glm::dot(light.lsEmitNormal, w);
        b.dirX[k] = w.x;
        b.dirY[k] = w.y;
        b.dirZ[k] = w.z;
        b.tfar[k] = std::max(0.0f, dist - margin);
        b.weight[k] = (k < count && cosP > 0.0f && cosY > 0.0f) ? cosP * cosY / r2 : 0.0f;
    }
}

}  // namespace so
