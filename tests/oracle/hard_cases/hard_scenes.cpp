#include "hard_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "core/channels.h"
#include "embree/embree_handles.h"
#include "oracle/accel.h"
#include "oracle/hard_shadow.h"
#include "oracle/offset.h"
#include "oracle/surface_buffer.h"

namespace so::test::hard {

namespace ch = channels;

double snap(double v, int bits) {
    return std::ldexp(std::nearbyint(std::ldexp(v, bits)), -bits);
}

glm::dvec3 snap(const glm::dvec3& v, int bits) {
    return {snap(v.x, bits), snap(v.y, bits), snap(v.z, bits)};
}

void snapScene(Scene& scene, int bits) {
    for (MeshPrimitive& m : scene.meshes)
        for (glm::dvec3& p : m.wsPositions) p = snap(p, bits);
    scene.camera.wsEye = snap(scene.camera.wsEye, bits);
    scene.camera.wsTarget = snap(scene.camera.wsTarget, bits);
    for (Light& l : scene.lights) {
        l.wsPosition = snap(l.wsPosition, bits);
        l.wsU = snap(l.wsU, bits);
        l.wsV = snap(l.wsV, bits);
    }
    finalizeScene(scene);
}

namespace {

struct IcoBuilder {
    std::vector<glm::dvec3> unit;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    uint32_t midpoint(uint32_t a, uint32_t b) {
        auto key = std::minmax(a, b);
        auto it = midpoints.find(key);
        if (it != midpoints.end()) return it->second;
        unit.push_back(glm::normalize(unit[a] + unit[b]));
        return midpoints[key] = uint32_t(unit.size() - 1);
    }
};

}  // namespace

MeshPrimitive makeIcosphere(const glm::dvec3& c, double r, int subdivisions,
                            const std::string& name) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    IcoBuilder b;
    for (const glm::dvec3& v :
         {glm::dvec3(-1, t, 0), glm::dvec3(1, t, 0), glm::dvec3(-1, -t, 0), glm::dvec3(1, -t, 0),
          glm::dvec3(0, -1, t), glm::dvec3(0, 1, t), glm::dvec3(0, -1, -t), glm::dvec3(0, 1, -t),
          glm::dvec3(t, 0, -1), glm::dvec3(t, 0, 1), glm::dvec3(-t, 0, -1), glm::dvec3(-t, 0, 1)})
        b.unit.push_back(glm::normalize(v));
    std::vector<uint32_t> idx = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int s = 0; s < subdivisions; ++s) {
        std::vector<uint32_t> next;
        for (size_t i = 0; i < idx.size(); i += 3) {
            uint32_t a = idx[i], bb = idx[i + 1], cc = idx[i + 2];
            uint32_t ab = b.midpoint(a, bb), bc = b.midpoint(bb, cc), ca = b.midpoint(cc, a);
            next.insert(next.end(), {a, ab, ca, bb, bc, ab, cc, ca, bc, ab, bc, ca});
        }
        idx = std::move(next);
    }
    MeshPrimitive m;
    m.name = name;
    for (const glm::dvec3& u : b.unit) m.wsPositions.push_back(c + r * u);
    m.indices = std::move(idx);
    return m;
}

glm::dmat3 randomRotation(uint64_t seed) {
    // SplitMix64, then a unit quaternion from three uniforms (Shoemake).
    auto next = [&seed]() {
        uint64_t z = (seed += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    };
    const double u1 = next(), u2 = 2.0 * std::numbers::pi * next(),
                 u3 = 2.0 * std::numbers::pi * next();
    const double a = std::sqrt(1 - u1), bq = std::sqrt(u1);
    const double w = a * std::sin(u2), x = a * std::cos(u2), y = bq * std::sin(u3),
                 z = bq * std::cos(u3);
    // Column-major: m[col][row].
    return glm::dmat3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),
                      2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),
                      2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
}

void rotateMesh(MeshPrimitive& mesh, const glm::dmat3& r, const glm::dvec3& center) {
    for (glm::dvec3& p : mesh.wsPositions) p = center + r * (p - center);
}

OracleResult runHard(const Scene& scene, PenumbraMethod penumbra) {
    OracleOptions o;
    o.penumbra.method = penumbra;
    return runOracle(scene, o);
}

std::vector<std::string> invariantChannels(const Scene& scene) {
    std::vector<std::string> names = {ch::kHit, ch::kMeshId, ch::kPrimId};
    for (const Light& l : scene.lights) {
        names.push_back(ch::lightChannel(l.name, ch::kVisibility));
        names.push_back(ch::lightChannel(l.name, ch::kCosine));
    }
    return names;
}

int differingChannels(const ChannelImage& a, const ChannelImage& b,
                      const std::vector<std::string>& names, std::string* first) {
    int n = 0;
    for (const std::string& name : names) {
        if (std::memcmp(a.channel(name), b.channel(name), a.pixelCount() * sizeof(float)) == 0)
            continue;
        if (n++ == 0 && first) *first = name;
    }
    return n;
}

size_t nonFiniteValues(const ChannelImage& img) {
    size_t bad = 0;
    for (const std::string& name : img.names()) {
        const bool mayBeInf = name == ch::kDepth || name.ends_with(ch::kOccluderDistance);
        const float* c = img.channel(name);
        for (size_t i = 0; i < img.pixelCount(); ++i)
            bad += std::isnan(c[i]) || (!mayBeInf && std::isinf(c[i]));
    }
    return bad;
}

glm::dvec3 hitPoint(const ChannelImage& img, size_t i) {
    return {img.channel(ch::kPX)[i], img.channel(ch::kPY)[i], img.channel(ch::kPZ)[i]};
}

namespace {

SurfaceBuffer emptyRow(size_t n) {
    SurfaceBuffer sb;
    sb.width = int(n);
    sb.height = 1;
    sb.tilesX = (sb.width + SurfaceBuffer::kTile - 1) / SurfaceBuffer::kTile;
    sb.tilesY = 1;
    const size_t slots = size_t(sb.tilesX) * 16;
    sb.hit.assign(slots, 0);
    sb.meshId.assign(slots, 0);
    sb.primId.assign(slots, 0);
    sb.originId.assign(slots, kNoOriginTriangle);
    for (auto* v : {&sb.lsPointX, &sb.lsPointY, &sb.lsPointZ, &sb.lsNormalX, &sb.lsNormalY,
                    &sb.lsNormalZ, &sb.lsOriginX, &sb.lsOriginY, &sb.lsOriginZ})
        v->assign(slots, 0.0f);
    sb.wsDepth.assign(slots, 1.0f);
    sb.tangentCos.assign(slots, std::numeric_limits<float>::infinity());
    return sb;
}

// One receiver point, as tracePrimary would fill it (surface_buffer.cpp).
bool probePoint(const Accel& accel, const glm::dvec3& ls, const glm::dvec3& n, SurfaceBuffer& sb,
                size_t s) {
    const glm::vec3 org(ls - 0x1.0p-10 * n), dir(n);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = org.x, rh.ray.org_y = org.y, rh.ray.org_z = org.z;
    rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
    rh.ray.tfar = 0x1.0p-9f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = kNoOriginTriangle;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(accel.rtcScene(), &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    glm::dvec3 a, b, c;
    accel.triangle(rh.hit.geomID, rh.hit.primID, a, b, c);
    const glm::dvec3 p =
        (1.0 - rh.hit.u - rh.hit.v) * a + double(rh.hit.u) * b + double(rh.hit.v) * c;
    const glm::vec3 pf(p), nf(n), o = errorBoundOrigin(p, n);
    sb.hit[s] = 1;
    sb.meshId[s] = rh.hit.geomID;
    sb.primId[s] = rh.hit.primID;
    sb.originId[s] = accel.originId(rh.hit.geomID, rh.hit.primID);
    sb.lsPointX[s] = pf.x, sb.lsPointY[s] = pf.y, sb.lsPointZ[s] = pf.z;
    sb.lsNormalX[s] = nf.x, sb.lsNormalY[s] = nf.y, sb.lsNormalZ[s] = nf.z;
    sb.lsOriginX[s] = o.x, sb.lsOriginY[s] = o.y, sb.lsOriginZ[s] = o.z;
    sb.tangentCos[s] = originTangencyBound(a, b, c);
    sb.lsMaxOffset = std::max(sb.lsMaxOffset, glm::length(glm::dvec3(o) - p));
    return true;
}

}  // namespace

PointVisibility oracleVisibilityAt(const Scene& scene, size_t light,
                                   const std::vector<glm::dvec3>& wsPoints,
                                   const glm::dvec3& wsNormal) {
    EmbreeDevice device;
    const Accel accel(scene, device);
    const LocalFrame& frame = accel.frame();
    SurfaceBuffer sb = emptyRow(wsPoints.size());
    PointVisibility out;
    setEmbreeFloatMode();
    for (size_t k = 0; k < wsPoints.size(); ++k) {
        const size_t s = sb.slot(int(k), 0);
        if (!probePoint(accel, frame.lsFromWs(wsPoints[k]), wsNormal, sb, s)) ++out.missed;
        out.wsPoints.push_back(frame.wsFromLs(glm::dvec3(sb.lsPoint(s))));
    }
    std::vector<float> cosine(wsPoints.size());
    out.V.assign(wsPoints.size(), 0.0f);
    traceHardShadows(accel, sb, makeHardLight(scene.lights[light], frame),
                     {out.V.data(), cosine.data(), nullptr}, nullptr);
    out.blindDistance = frame.wsLength(sb.lsMaxOffset);
    return out;
}

bool segmentHitsBox(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& lo,
                    const glm::dvec3& hi, double e) {
    const glm::dvec3 d = q - p;
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 3; ++k) {
        const double l = lo[k] - e, h = hi[k] + e;
        if (l > h) return false;
        if (d[k] == 0.0) {
            if (p[k] < l || p[k] > h) return false;
            continue;
        }
        const double a = (l - p[k]) / d[k], b = (h - p[k]) / d[k];
        t0 = std::max(t0, std::min(a, b));
        t1 = std::min(t1, std::max(a, b));
    }
    return t0 <= t1;
}

double boxMargin(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& lo,
                 const glm::dvec3& hi, double eMax) {
    auto agree = [&](double e) {
        return segmentHitsBox(p, q, lo, hi, e) == segmentHitsBox(p, q, lo, hi, -e);
    };
    if (agree(eMax)) return eMax;
    double a = 0.0, b = eMax;  // agree(a), !agree(b)
    for (int i = 0; i < 64 && b - a > eMax * 0x1.0p-50; ++i) {
        const double m = 0.5 * (a + b);
        (agree(m) ? a : b) = m;
    }
    return a;
}

}  // namespace so::test::hard
