#include "oracle/disk_bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace so {

namespace {

using glm::dvec3;

// The polygons' circles are this much smaller (P_in) and larger (P_out) than the disk, relative:
// twice the largest move of a vertex by the quantisation (sqrt(2)/2 of 2^-29 of the frame's
// 2.5 radii: 2^-28.2 radii), so the quantised polygons keep P_in in disk in P_out.
constexpr double kSlack = 1.0 / 134217728.0;  // 2^-27
// Added to both ends of an interval where any shadow reached the light: the quantisation of the
// shadows' vertices (polygon_visibility.h) moves V by about 1e-9 (at most 2.2e-9 measured against
// the closed form of a rect light over a square), which the polygons' bound does not hold.
constexpr double kQuantisationAllowance = 1e-8;
// The gathering's base polygon: the octagon circumscribed about 1.09 radii, which holds every
// P_out from 8 sides on (their vertices are at most (1 + kSlack) / cos(pi/8) = 1.0824 radii out).
constexpr double kBaseScale = 1.09;

// cos and sin of 2 pi k / (2 kMaxDiskSides), computed once: the polygons of every pixel share them.
const std::vector<std::array<double, 2>>& unitCircle() {
    static const std::vector<std::array<double, 2>> table = [] {
        const size_t count = 2 * size_t(kMaxDiskSides);
        std::vector<std::array<double, 2>> t(count);
        for (size_t k = 0; k < count; ++k) {
            const double a = 2.0 * std::numbers::pi * double(k) / double(count);
            t[k] = {std::cos(a), std::sin(a)};
        }
        return t;
    }();
    return table;
}

bool validSides(uint32_t sides) {
    return sides >= 8 && sides <= kMaxDiskSides && (sides & (sides - 1)) == 0;
}

// Vertex k of the n-gon whose vertices lie at `radius` and angles 2 pi (k + offset/2) / n.
std::vector<dvec3> regularPolygon(const DiskLightShape& disk, uint32_t sides, double radius,
                                  uint32_t offset) {
    SO_CHECK(validSides(sides));
    const auto& circle = unitCircle();
    const size_t step = circle.size() / sides;
    std::vector<dvec3> out(sides);
    for (uint32_t k = 0; k < sides; ++k) {
        const std::array<double, 2>& cs = circle[size_t(k) * step + offset * (step / 2)];
        out[k] = disk.center + radius * (cs[0] * disk.e1 + cs[1] * disk.e2);
    }
    return out;
}

}  // namespace

void diskAxes(const dvec3& m, dvec3& e1, dvec3& e2) {
    const dvec3 helper = std::fabs(m.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    e1 = glm::normalize(glm::cross(helper, m));
    e2 = glm::cross(m, e1);
}

DiskLightShape sphereSilhouette(const dvec3& center, double radius, const dvec3& p) {
    const dvec3 w = center - p;
    const double d2 = glm::dot(w, w), d = std::sqrt(d2);
    SO_CHECK_LT(radius, d);
    DiskLightShape disk;
    const double r2 = radius * radius;
    disk.center = p + w * ((d2 - r2) / d2);
    disk.radius = radius * std::sqrt((d2 - r2) / d2);
    disk.emitNormal = -w / d;
    diskAxes(disk.emitNormal, disk.e1, disk.e2);
    return disk;
}

bool diskAboveHorizon(const DiskLightShape& disk, const dvec3& p, const dvec3& n) {
    const double nm = glm::dot(n, disk.emitNormal);
    return glm::dot(n, disk.center - p) - disk.radius * std::sqrt(std::max(0.0, 1.0 - nm * nm)) >
           0.0;
}

double diskSolidAngle(const DiskLightShape& disk, const dvec3& p, const dvec3& n) {
    // p at height h over the disk's plane, a from its axis; the vector irradiance (1/2) the
    // integral of (r x dr) / |r|^2 around the circle has closed-form components along the axis
    // and towards p's foot (a computer-algebra-free derivation: docs/oracle.md).
    const double r = disk.radius, r2 = r * r;
    const dvec3 w = p - disk.center;
    const double h = glm::dot(disk.emitNormal, w);
    const dvec3 inPlane = w - h * disk.emitNormal;  // a e1
    const double a2 = glm::dot(inPlane, inPlane), a = std::sqrt(a2);
    const double A = r2 + a2 + h * h;
    const double S = std::sqrt(((r - a) * (r - a) + h * h) * ((r + a) * (r + a) + h * h));
    const double Q = r2 + h * h - a2;
    // Q + S without cancellation: S^2 - Q^2 = 4 a^2 h^2.
    const double QS = Q >= 0.0 ? Q + S : 4.0 * a2 * h * h / (S - Q);
    const double scale = std::numbers::pi * r2 / (S * (A + S));
    const dvec3 towardLight = -(2.0 * h * inPlane + QS * disk.emitNormal) * scale;
    return glm::dot(n, towardLight);
}

std::vector<dvec3> inscribedPolygon(const DiskLightShape& disk, uint32_t sides, double scale) {
    return regularPolygon(disk, sides, disk.radius * scale, 0);
}

std::vector<dvec3> circumscribedPolygon(const DiskLightShape& disk, uint32_t sides, double scale) {
    // Vertices halfway between the tangent points, 1 / cos(pi / n) out.
    const double pi = std::numbers::pi;
    return regularPolygon(disk, sides, disk.radius * scale / std::cos(pi / double(sides)), 1);
}

DiskArc diskArcAbove(const DiskLightShape& disk, const dvec3& p, const dvec3& n) {
    // The circle's height over p's plane: H + r S cos(t - centre).
    const double H = glm::dot(n, disk.center - p);
    const double a = glm::dot(n, disk.e1), b = glm::dot(n, disk.e2);
    const double S = std::sqrt(a * a + b * b);
    DiskArc arc;
    arc.center = std::atan2(b, a);
    const double c = -H / (disk.radius * S);
    arc.half = !(c > -1.0) ? std::numbers::pi : c >= 1.0 ? 0.0 : std::acos(c);
    return arc;
}

namespace {

// The angles of a polygon's vertices (inscribed) or tangent points (circumscribed): `sides`
// equal steps over the arc, its ends included, then steps of at most a quarter turn round the
// rest of the circle.
std::vector<double> arcAngles(uint32_t sides, const DiskArc& arc) {
    const double pi = std::numbers::pi;
    std::vector<double> t;
    t.reserve(sides + 4);
    const double start = arc.center - arc.half, step = 2.0 * arc.half / double(sides);
    for (uint32_t k = 0; k <= sides; ++k) t.push_back(start + step * double(k));
    const double rest = 2.0 * pi - 2.0 * arc.half;
    const int coarse = std::max(1, int(std::ceil(rest / (0.5 * pi))));
    for (int j = 1; j < coarse; ++j) t.push_back(arc.center + arc.half + rest * j / coarse);
    return t;
}

dvec3 onCircle(const DiskLightShape& disk, double radius, double t) {
    return disk.center + radius * (std::cos(t) * disk.e1 + std::sin(t) * disk.e2);
}

}  // namespace

std::vector<dvec3> inscribedPolygon(const DiskLightShape& disk, uint32_t sides, double scale,
                                    const DiskArc& arc) {
    if (arc.half >= std::numbers::pi) return inscribedPolygon(disk, sides, scale);
    std::vector<dvec3> out;
    for (double t : arcAngles(sides, arc)) out.push_back(onCircle(disk, disk.radius * scale, t));
    return out;
}

std::vector<dvec3> circumscribedPolygon(const DiskLightShape& disk, uint32_t sides, double scale,
                                        const DiskArc& arc) {
    if (arc.half >= std::numbers::pi) return circumscribedPolygon(disk, sides, scale);
    // Consecutive tangent lines (at t0 and t1, less than half a turn apart) meet at the middle
    // angle, 1 / cos(half the gap) out.
    const std::vector<double> t = arcAngles(sides, arc);
    std::vector<dvec3> out;
    for (size_t i = 0; i < t.size(); ++i) {
        const double t0 = t[i], t1 = i + 1 < t.size() ? t[i + 1] : t[0] + 2.0 * std::numbers::pi;
        const double half = 0.5 * (t1 - t0);
        out.push_back(onCircle(disk, disk.radius * scale / std::cos(half), t0 + half));
    }
    return out;
}

PolygonLightShape diskGatheringShape(const DiskLightShape& disk, uint32_t sides, double scale) {
    PolygonLightShape base;
    const double h = kDiskFrameHalfSide * disk.radius;
    base.corner = disk.center - h * disk.e1 - h * disk.e2;
    base.edgeU = 2.0 * h * disk.e1;
    base.edgeV = 2.0 * h * disk.e2;
    base.emitNormal = disk.emitNormal;
    base.vertices = circumscribedPolygon(disk, sides, scale);
    return base;
}

LightShadows diskShadows(const ExactTracer& tracer, const DiskLightShape& disk, const dvec3& p,
                         const dvec3& n, TriangleId self, uint32_t maxCandidates,
                         const OccluderOptions& more) {
    return LightShadows(tracer, diskGatheringShape(disk, 8, kBaseScale), p, n, self, maxCandidates,
                        more);
}

DiskBound diskBoundAt(const LightShadows& shadows, const DiskLightShape& disk, const dvec3& p,
                      const dvec3& n, uint32_t sides) {
    // The polygons' sides go to the arc above the horizon: where it cuts the disk to a sliver,
    // regular polygons would spend nearly all of them below it.
    const DiskArc arc = diskArcAbove(disk, p, n);
    if (!(arc.half > 0.0)) return {0.0, 0.0};
    const LightShadows::Integrals in =
        shadows.integrals(inscribedPolygon(disk, sides, 1.0 - kSlack, arc));
    const LightShadows::Integrals out =
        shadows.integrals(circumscribedPolygon(disk, sides, 1.0 + kSlack, arc));
    if (!(out.whole > 0.0)) return {0.0, 0.0};  // no part of P_out, so of the disk, is lit
    double uLo = in.whole, uHi = out.whole;
    if (diskAboveHorizon(disk, p, n)) uLo = uHi = diskSolidAngle(disk, p, n);
    const double oIn = std::max(0.0, in.whole - in.visible);
    const double oOut = std::max(0.0, out.whole - out.visible);
    // uLo may be 0 (no part of P_in above the horizon): the divisions give +-inf, which the
    // clamps below turn into the trivial bound.
    double lower = std::max(in.visible / uHi, 1.0 - oOut / uLo);
    double upper = std::min(out.visible / uLo, 1.0 - oIn / uHi);
    lower = std::clamp(std::isnan(lower) ? 0.0 : lower, 0.0, 1.0);
    upper = std::clamp(std::isnan(upper) ? 1.0 : upper, 0.0, 1.0);
    if (lower > upper) lower = upper = 0.5 * (lower + upper);  // rounding, where the width is 0
    return {lower, upper};
}

DiskVisibility diskLightVisibility(const ExactTracer& tracer, const DiskLightShape& disk,
                                   const dvec3& p, const dvec3& n, TriangleId self,
                                   uint32_t maxCandidates, const DiskBoundOptions& options,
                                   const OccluderOptions& more) {
    SO_CHECK(validSides(options.minSides) && validSides(options.maxSides));
    DiskVisibility out;
    // The gathering polygon is larger than the disk: it may reach above the horizon where the disk
    // does not. Then no light (NoLight, V = 0), not the "nothing in the pyramid" below.
    if (!(diskArcAbove(disk, p, n).half > 0.0)) return out;
    const LightShadows shadows = diskShadows(tracer, disk, p, n, self, maxCandidates, more);
    out.counts = shadows.counts();
    if (out.counts.status != PolygonVisibilityStatus::Exact) return out;
    if (out.counts.occluders == 0) {  // nothing in the pyramid: every region is wholly visible
        out.lower = out.upper = out.counts.V = 1.0;
        return out;
    }
    // The shadows cover the gathering polygon above the horizon, so the disk's part above it:
    // V = 0 but for the shadows' quantisation, as every bound below allows for it.
    if (out.counts.shortcut == VisibilityShortcut::Covered) {
        out.lower = 0.0;
        out.upper = kQuantisationAllowance;
        out.counts.V = 0.5 * (out.lower + out.upper);
        return out;
    }
    for (uint32_t sides = options.minSides;;) {
        const DiskBound b = diskBoundAt(shadows, disk, p, n, sides);
        out.lower = std::max(0.0, b.lower - kQuantisationAllowance);
        out.upper = std::min(1.0, b.upper + kQuantisationAllowance);
        out.sides = sides;
        const double half = 0.5 * (b.upper - b.lower);
        if (out.halfWidth() <= options.targetHalfWidth) break;
        if (sides >= options.maxSides) {
            out.reachedTarget = false;
            break;
        }
        // Doubling, but past the counts the 1/n^2 fall already rules out: the sides whose width
        // that fall predicts at the target (the prediction only skips work; each count's own
        // bound decides).
        const double wanted =
            double(sides) * std::sqrt(half / std::max(options.targetHalfWidth - 1e-8, 1e-12));
        sides *= 2;
        while (sides < options.maxSides && double(sides) < wanted) sides *= 2;
    }
    out.counts.V = 0.5 * (out.lower + out.upper);
    return out;
}

}  // namespace so
