#include "oracle/disk_exact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace so {

namespace {

using glm::dvec2;
using glm::dvec3;

constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// Added to V's error wherever a shadow reached the light: the shadows' vertices are quantised
// (polygon_visibility.h), which moves V by about 1e-9 (as for rect lights; disk_bounds.h).
constexpr double kQuantisationAllowance = 1e-8;
// The gathering octagon's edges lie this far (relative) outside the circle: far more than the
// quantisation moves them (2^-28 of the radius), so they never cross it.
constexpr double kOctagonScale = 1.0 + 1.0 / 1048576.0;  // 1 + 2^-20
// Arcs are cut to at most this before the adaptive rule, and halved where the two rules differ by
// more than kArcTolerance of the scale, at most kMaxArcDepth times.
constexpr double kMaxArc = kPi / 2.0;
constexpr double kArcTolerance = 1e-14;
constexpr int kMaxArcDepth = 24;
// The rounding allowance: ulps of the sum of the terms' magnitudes.
constexpr double kRoundingUlps = 16.0;

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the recurrence), computed once.
template <int N>
struct GaussLegendre {
    std::array<double, N> x{}, w{};
    GaussLegendre() {
        for (int i = 0; i < N; ++i) {
            double z = std::cos(kPi * (double(i) + 0.75) / (double(N) + 0.5)), dp = 0.0;
            for (int iter = 0; iter < 100; ++iter) {
                double p0 = 1.0, p1 = 0.0;
                for (int k = 1; k <= N; ++k) {
                    const double p2 = p1;
                    p1 = p0;
                    p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / double(k);
                }
                dp = double(N) * (z * p0 - p1) / (z * z - 1.0);
                const double dz = p0 / dp;
                z -= dz;
                if (std::fabs(dz) < 1e-17) break;
            }
            x[size_t(i)] = z;
            w[size_t(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
        }
    }
};
const GaussLegendre<16>& rule16() {
    static const GaussLegendre<16> r;
    return r;
}
const GaussLegendre<32>& rule32() {
    static const GaussLegendre<32> r;
    return r;
}

// Lambert's integrand along the circle, (1/2) n . (r x r') / |r|^2 at angle t, r = w + R(cos t e1
// + sin t e2): with q = n x w, n . (w x r') = r' . q, and n . (R u x r') = R^2 n . (e1 x e2).
struct ArcIntegrand {
    dvec3 w, e1, e2;
    double R = 0.0, qe1 = 0.0, qe2 = 0.0, k = 0.0;
    ArcIntegrand(const DiskLightShape& disk, const dvec3& p, const dvec3& n)
        : w(disk.center - p), e1(disk.e1), e2(disk.e2), R(disk.radius) {
        const dvec3 q = glm::cross(n, w);
        qe1 = R * glm::dot(q, e1);
        qe2 = R * glm::dot(q, e2);
        k = R * R * glm::dot(n, glm::cross(e1, e2));
    }
    double operator()(double t) const {
        const double c = std::cos(t), s = std::sin(t);
        const dvec3 r = w + (R * c) * e1 + (R * s) * e2;
        return 0.5 * (c * qe2 - s * qe1 + k) / glm::dot(r, r);
    }
};

template <int N>
double gauss(const GaussLegendre<N>& rule, const ArcIntegrand& f, double t0, double t1) {
    const double mid = 0.5 * (t0 + t1), half = 0.5 * (t1 - t0);
    double sum = 0.0;
    for (size_t i = 0; i < size_t(N); ++i) sum += rule.w[i] * f(mid + half * rule.x[i]);
    return half * sum;
}

// The contour's running sum: value, stated error, and the terms' magnitudes for the rounding.
struct Contour {
    double value = 0.0, error = 0.0, magnitude = 0.0;
    void add(double term, double termError) {
        value += term;
        error += termError;
        magnitude += std::fabs(term);
    }
};

void addArcAdaptive(const ArcIntegrand& f, double t0, double t1, double scale, int depth,
                    Contour& out) {
    const double coarse = gauss(rule16(), f, t0, t1), fine = gauss(rule32(), f, t0, t1);
    const double diff = std::fabs(fine - coarse);
    if (diff <= kArcTolerance * scale || depth >= kMaxArcDepth) {
        out.add(fine, diff);
        return;
    }
    const double mid = 0.5 * (t0 + t1);
    addArcAdaptive(f, t0, mid, scale, depth + 1, out);
    addArcAdaptive(f, mid, t1, scale, depth + 1, out);
}

// The arc from t0 to t1 > t0, counter-clockwise.
void addArc(const ArcIntegrand& f, double t0, double t1, double scale, Contour& out) {
    const int pieces = std::max(1, int(std::ceil((t1 - t0) / kMaxArc)));
    for (int i = 0; i < pieces; ++i) {
        const double a = t0 + (t1 - t0) * double(i) / double(pieces);
        const double b = i + 1 == pieces ? t1 : t0 + (t1 - t0) * double(i + 1) / double(pieces);
        addArcAdaptive(f, a, b, scale, 0, out);
    }
}

dvec3 relative(const DiskLightShape& disk, const dvec3& w, const dvec2& uv) {
    return w + uv.x * disk.e1 + uv.y * disk.e2;
}

// The scale the arcs' tolerance is relative to: about Phi of the whole disk.
double integralScale(const DiskLightShape& disk, const dvec3& p) {
    const dvec3 w = disk.center - p;
    const double r2 = disk.radius * disk.radius;
    return kPi * r2 / (glm::dot(w, w) + r2);
}

// The contour's orientation: counter-clockwise about e1 x e2 (the emitting normal) runs
// clockwise as seen from p on the emitting side, where Lambert's integral is negative.
double orientation(const DiskLightShape& disk, const dvec3& p) {
    return glm::dot(glm::cross(disk.e1, disk.e2), p - disk.center) > 0.0 ? -1.0 : 1.0;
}

DiskIntegral finish(const Contour& c, double sign) {
    return {sign * c.value, c.error + kRoundingUlps * kEps * c.magnitude};
}

// Whether q lies inside the region (non-zero winding number over its paths).
bool inside(const std::vector<std::vector<dvec2>>& region, const dvec2& q) {
    int winding = 0;
    for (const std::vector<dvec2>& path : region) {
        const size_t count = path.size();
        for (size_t i = 0; i < count; ++i) {
            const dvec2 a = path[i], b = path[(i + 1) % count];
            const double side = (b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y);
            if (a.y <= q.y) {
                if (b.y > q.y && side > 0.0) ++winding;
            } else if (b.y <= q.y && side < 0.0) {
                --winding;
            }
        }
    }
    return winding != 0;
}

// The frame's integers as (u, v) about the centre: (X - 2^28) / 2^28 half-sides.
std::vector<std::vector<dvec2>> regionOf(const ClipperLib::Paths& paths,
                                         const DiskLightShape& disk) {
    const double half = 0.5 * LightPlaneFrame::kQuantum;
    const double unit = kDiskFrameHalfSide * disk.radius / half;
    std::vector<std::vector<dvec2>> out;
    out.reserve(paths.size());
    for (const ClipperLib::Path& path : paths) {
        std::vector<dvec2> uv;
        uv.reserve(path.size());
        for (const ClipperLib::IntPoint& q : path)
            uv.push_back({(double(q.X) - half) * unit, (double(q.Y) - half) * unit});
        out.push_back(std::move(uv));
    }
    return out;
}

}  // namespace

DiskIntegral diskUnoccludedSolidAngle(const DiskLightShape& disk, const dvec3& p, const dvec3& n) {
    const DiskArc arc = diskArcAbove(disk, p, n);
    if (!(arc.half > 0.0)) return {};
    if (diskAboveHorizon(disk, p, n)) {
        // Its rounding relative to the vector irradiance's size (about the scale), not to the
        // value: a disk near the horizon takes the value as a difference.
        const double v = diskSolidAngle(disk, p, n);
        return {v, kRoundingUlps * kEps * (std::fabs(v) + integralScale(disk, p))};
    }
    // The arc above the horizon, counter-clockwise, and the chord back along the horizon.
    const ArcIntegrand f(disk, p, n);
    const double t0 = arc.center - arc.half, t1 = arc.center + arc.half;
    Contour c;
    addArc(f, t0, t1, integralScale(disk, p), c);
    const dvec2 a(disk.radius * std::cos(t1), disk.radius * std::sin(t1));
    const dvec2 b(disk.radius * std::cos(t0), disk.radius * std::sin(t0));
    c.add(lambertEdge(relative(disk, f.w, a), relative(disk, f.w, b), n), 0.0);
    const DiskIntegral out = finish(c, orientation(disk, p));
    return {std::max(0.0, out.value), out.error};
}

DiskIntegral diskRegionSolidAngle(const DiskLightShape& disk, const dvec3& p, const dvec3& n,
                                  const std::vector<std::vector<dvec2>>& region) {
    const ArcIntegrand f(disk, p, n);
    const double R = disk.radius;
    Contour c;
    // P's edges inside the disk, and where they cross the circle.
    std::vector<double> crossings;
    for (const std::vector<dvec2>& path : region) {
        const size_t count = path.size();
        for (size_t i = 0; i < count; ++i) {
            const dvec2 a = path[i], d = path[(i + 1) % count] - a;
            // |a + s d|^2 = R^2, the roots without cancellation.
            const double dd = glm::dot(d, d), ad = glm::dot(a, d);
            if (!(dd > 0.0)) continue;
            const double aa = (glm::length(a) - R) * (glm::length(a) + R);
            const double disc = ad * ad - dd * aa;
            if (!(disc > 0.0)) continue;  // the line misses the open disk
            const double q = -(ad + std::copysign(std::sqrt(disc), ad));
            double s0 = q / dd, s1 = aa / q;
            if (s0 > s1) std::swap(s0, s1);
            const double lo = std::max(s0, 0.0), hi = std::min(s1, 1.0);
            if (!(lo < hi)) continue;
            const dvec2 x0 = a + lo * d, x1 = a + hi * d;
            c.add(lambertEdge(relative(disk, f.w, x0), relative(disk, f.w, x1), n), 0.0);
            // A crossing too many only splits an arc; one too few would join two.
            if (s0 >= 0.0) crossings.push_back(std::atan2(x0.y, x0.x));
            if (s1 <= 1.0) crossings.push_back(std::atan2(x1.y, x1.x));
        }
    }
    // The arcs between the crossings that lie inside P.
    const double scale = integralScale(disk, p);
    if (crossings.empty()) {
        if (inside(region, {R, 0.0})) addArc(f, 0.0, 2.0 * kPi, scale, c);
    } else {
        std::sort(crossings.begin(), crossings.end());
        for (size_t i = 0; i < crossings.size(); ++i) {
            const double t0 = crossings[i];
            const double t1 =
                i + 1 < crossings.size() ? crossings[i + 1] : crossings[0] + 2.0 * kPi;
            if (!(t1 > t0)) continue;
            const double mid = 0.5 * (t0 + t1);
            if (inside(region, {R * std::cos(mid), R * std::sin(mid)})) addArc(f, t0, t1, scale, c);
        }
    }
    return finish(c, orientation(disk, p));
}

DiskExactVisibility diskLightExact(const ExactTracer& tracer, const DiskLightShape& disk,
                                   const dvec3& p, const dvec3& n, TriangleId self,
                                   uint32_t maxCandidates, const OccluderOptions& more) {
    DiskExactVisibility out;
    // The octagon may reach above the horizon where the disk does not: then no light (V = 0).
    if (!(diskArcAbove(disk, p, n).half > 0.0)) return out;
    const LightShadows shadows(tracer, diskGatheringShape(disk, kDiskGatheringSides, kOctagonScale),
                               p, n, self, maxCandidates, more);
    out.counts = shadows.counts();
    if (out.counts.status != PolygonVisibilityStatus::Exact) return out;
    if (out.counts.occluders == 0) {  // nothing in the pyramid: the disk is wholly visible
        out.counts.V = 1.0;
        return out;
    }
    // The shadows cover the octagon above the horizon, so the disk's part above it: V = 0 but
    // for the shadows' quantisation.
    if (out.counts.shortcut == VisibilityShortcut::Covered) {
        out.error = kQuantisationAllowance;
        return out;
    }
    const DiskIntegral whole = diskUnoccludedSolidAngle(disk, p, n);
    if (!(whole.value > 0.0)) {  // the disk's part above the horizon is too thin to light p
        out.counts.status = PolygonVisibilityStatus::NoLight;
        return out;
    }
    const DiskIntegral seen =
        diskRegionSolidAngle(disk, p, n, regionOf(shadows.visiblePaths(), disk));
    out.sides = kDiskGatheringSides;
    const double V = std::clamp(seen.value / whole.value, 0.0, 1.0);
    out.counts.V = V;
    out.error = (seen.error + V * whole.error) / whole.value + 2.0 * kEps + kQuantisationAllowance;
    return out;
}

}  // namespace so
