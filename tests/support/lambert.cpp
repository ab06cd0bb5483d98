#include "lambert.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace so::test {
namespace {

// Keeps the part of a convex polygon with dot(n, y - p) >= 0 (Sutherland-Hodgman, one plane).
std::vector<glm::dvec3> clipAboveHorizon(const glm::dvec3& p, const glm::dvec3& n,
                                         const std::vector<glm::dvec3>& poly) {
    std::vector<glm::dvec3> out;
    const size_t count = poly.size();
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec3& a = poly[i];
        const glm::dvec3& b = poly[(i + 1) % count];
        const double da = glm::dot(n, a - p);
        const double db = glm::dot(n, b - p);
        if (da >= 0.0) out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

// Newell's normal: the polygon's area vector, robust for slightly non-planar input.
glm::dvec3 newellNormal(const std::vector<glm::dvec3>& poly) {
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < poly.size(); ++i)
        sum += glm::cross(poly[i], poly[(i + 1) % poly.size()]);
    return 0.5 * sum;
}

glm::dvec3 centroid(const std::vector<glm::dvec3>& poly) {
    glm::dvec3 c(0.0);
    for (const glm::dvec3& v : poly) c += v;
    return c / static_cast<double>(poly.size());
}

double rectArea(const AxisRect& r) {
    return (r.x1 - r.x0) * (r.z1 - r.z0);
}

// The light minus the occluder's shadow on the light's plane, as disjoint rectangles. `blocked`
// reports how the shadow meets the light so callers can return 0 and 1 exactly.
enum class Blocked { None, Partly, All };
struct Visible {
    Blocked blocked = Blocked::None;
    std::vector<AxisRect> pieces;
};

Visible visiblePieces(const glm::dvec3& p, const AxisRect& light, const AxisRect& occluder) {
    Visible vis;
    // At or above the occluder's plane every segment towards the (higher) light leaves that plane
    // at p itself, which the open segment excludes.
    if (!(p.y < occluder.y)) return vis;
    const double s = (light.y - p.y) / (occluder.y - p.y);
    const double sx0 = p.x + (occluder.x0 - p.x) * s, sx1 = p.x + (occluder.x1 - p.x) * s;
    const double sz0 = p.z + (occluder.z0 - p.z) * s, sz1 = p.z + (occluder.z1 - p.z) * s;
    const double ix0 = std::max(light.x0, sx0), ix1 = std::min(light.x1, sx1);
    const double iz0 = std::max(light.z0, sz0), iz1 = std::min(light.z1, sz1);
    // A shadow touching the light only along a line blocks a null set.
    if (!(ix0 < ix1 && iz0 < iz1)) return vis;
    if (ix0 <= light.x0 && ix1 >= light.x1 && iz0 <= light.z0 && iz1 >= light.z1) {
        vis.blocked = Blocked::All;
        return vis;
    }
    vis.blocked = Blocked::Partly;
    const double y = light.y;
    // Full-depth strips left and right of the shadow, then the parts above and below it.
    const AxisRect candidates[] = {{y, light.x0, ix0, light.z0, light.z1},
                                   {y, ix1, light.x1, light.z0, light.z1},
                                   {y, ix0, ix1, light.z0, iz0},
                                   {y, ix0, ix1, iz1, light.z1}};
    for (const AxisRect& r : candidates)
        if (r.x0 < r.x1 && r.z0 < r.z1) vis.pieces.push_back(r);
    return vis;
}

const glm::dvec3 kDown(0.0, -1.0, 0.0);

}  // namespace

double polygonIrradiance(const glm::dvec3& p, const glm::dvec3& n,
                         const std::vector<glm::dvec3>& poly, const glm::dvec3& emitNormal) {
    if (poly.size() < 3) return 0.0;
    const double nLen = glm::length(n), eLen = glm::length(emitNormal);
    if (!(nLen > 0.0) || !(eLen > 0.0)) return 0.0;
    const glm::dvec3 un = n / nLen;
    const glm::dvec3 c = centroid(poly);
    // One-sided emitter: cos_y <= 0 everywhere on the polygon when p is behind or in its plane.
    if (!(glm::dot(emitNormal, p - c) > 0.0)) return 0.0;
    // The sum's sign follows the winding as seen from p, so fix it from the geometry rather than
    // taking |sum|, which would hide a wrong-signed result from a broken polygon.
    const double facing = glm::dot(newellNormal(poly), c - p);
    if (facing == 0.0) return 0.0;

    const std::vector<glm::dvec3> clipped = clipAboveHorizon(p, un, poly);
    if (clipped.size() < 3) return 0.0;
    std::vector<glm::dvec3> dirs;
    dirs.reserve(clipped.size());
    for (const glm::dvec3& v : clipped) {
        const glm::dvec3 d = v - p;
        const double len = glm::length(d);
        if (!(len > 0.0)) return 0.0;  // p on the polygon: only possible in its plane
        dirs.push_back(d / len);
    }
    double sum = 0.0;
    for (size_t i = 0; i < dirs.size(); ++i) {
        const glm::dvec3 cr = glm::cross(dirs[i], dirs[(i + 1) % dirs.size()]);
        const double sinT = glm::length(cr);
        // Coincident directions (repeated or clipped-onto vertices) subtend no angle.
        if (!(sinT > 0.0)) continue;
        // atan2 keeps small and near-pi angles accurate where acos of the dot would not.
        const double theta = std::atan2(sinT, glm::dot(dirs[i], dirs[(i + 1) % dirs.size()]));
        sum += theta * glm::dot(un, cr) / sinT;
    }
    const double e = 0.5 * (facing > 0.0 ? sum : -sum);
    return std::max(0.0, e);
}

std::vector<glm::dvec3> axisRectPolygon(const AxisRect& r) {
    return {{r.x0, r.y, r.z0}, {r.x0, r.y, r.z1}, {r.x1, r.y, r.z1}, {r.x1, r.y, r.z0}};
}

double exactRectLightRectOccluderV(const glm::dvec3& p, const glm::dvec3& n, const AxisRect& light,
                                   const AxisRect& occluder) {
    const double total = polygonIrradiance(p, n, axisRectPolygon(light), kDown);
    if (!(total > 0.0)) return 0.0;
    const Visible vis = visiblePieces(p, light, occluder);
    if (vis.blocked == Blocked::None) return 1.0;
    if (vis.blocked == Blocked::All) return 0.0;
    double visible = 0.0;
    for (const AxisRect& r : vis.pieces)
        visible += polygonIrradiance(p, n, axisRectPolygon(r), kDown);
    return std::clamp(visible / total, 0.0, 1.0);
}

double exactRectLightUnweightedFraction(const glm::dvec3& p, const glm::dvec3& n,
                                        const AxisRect& light, const AxisRect& occluder) {
    if (!(polygonIrradiance(p, n, axisRectPolygon(light), kDown) > 0.0)) return 0.0;
    const Visible vis = visiblePieces(p, light, occluder);
    if (vis.blocked == Blocked::None) return 1.0;
    if (vis.blocked == Blocked::All) return 0.0;
    double visible = 0.0;
    for (const AxisRect& r : vis.pieces) visible += rectArea(r);
    return std::clamp(visible / rectArea(light), 0.0, 1.0);
}

}  // namespace so::test
