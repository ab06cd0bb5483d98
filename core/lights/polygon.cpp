// `polygon`: a one-sided planar convex polygon light with 3 to 64 `vertices`, counter-clockwise
// seen from the side it lights (so a rect's corners c -+ u/2 -+ v/2 in that order emit along
// cross(u, v), as the rect does). Checked here, once, so every layer may rely on it: planar within
// 1e-7 of its size (the diagonal of its bounding box), every turn strictly convex (no concave or
// collinear corner, no repeated vertex) and winding once, a positive area (docs/scene-format.md).
// The light's wsPosition is its area centroid (a point stand-in's place, as a rect's centre is)
// and wsNormal the unit normal of its lit side.
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "core/lights/light_kind.h"

namespace so {

namespace {

constexpr size_t kMinVertices = 3, kMaxVertices = 64;
constexpr double kPlanarTolerance = 1e-7;  // of the polygon's size
constexpr double kTurnTolerance = 1e-9;    // sine of the smallest turn accepted at a corner

std::string vertexField(const std::string& f, size_t k) {
    return f + ".vertices[" + std::to_string(k) + "]";
}

// Twice the vector area (Newell's method, about the first vertex for precision).
glm::dvec3 twiceVectorArea(const std::vector<glm::dvec3>& v) {
    glm::dvec3 sum(0.0);
    for (size_t k = 1; k + 1 < v.size(); ++k) sum += glm::cross(v[k] - v[0], v[k + 1] - v[0]);
    return sum;
}

void checkPlanar(const std::vector<glm::dvec3>& v, const glm::dvec3& n, double size,
                 const JsonReader& r, const std::string& f) {
    for (size_t k = 1; k < v.size(); ++k) {
        const double off = std::fabs(glm::dot(v[k] - v[0], n));
        if (off > kPlanarTolerance * size) {
            char text[160];
            std::snprintf(text, sizeof text,
                          "not in the plane of the others (%.3g off it; the tolerance is %.3g, "
                          "1e-7 of the polygon's size)",
                          off, kPlanarTolerance * size);
            r.fail(vertexField(f, k), text);
        }
    }
}

// Every corner turns the same way as the normal, and the fan from vertex 0 never folds back (a
// polygon that winds twice, a pentagram, turns left at every corner too).
void checkConvex(const std::vector<glm::dvec3>& v, const glm::dvec3& n, const JsonReader& r,
                 const std::string& f) {
    const size_t m = v.size();
    for (size_t k = 0; k < m; ++k) {
        const glm::dvec3 in = v[k] - v[(k + m - 1) % m], out = v[(k + 1) % m] - v[k];
        const double li = glm::length(in), lo = glm::length(out);
        if (!(lo > 0.0)) r.fail(vertexField(f, (k + 1) % m), "repeats the vertex before it");
        const double turn = glm::dot(glm::cross(in, out), n);
        if (!(turn > kTurnTolerance * li * lo))
            r.fail(vertexField(f, k), turn < 0.0 ? "the polygon is not convex at this vertex"
                                                 : "collinear with its neighbours (degenerate)");
    }
    for (size_t k = 1; k + 1 < m; ++k)
        if (!(glm::dot(glm::cross(v[k] - v[0], v[k + 1] - v[0]), n) > 0.0))
            r.fail(f + ".vertices", "the polygon winds more than once (not convex)");
}

class PolygonLightKind final : public LightKind {
  public:
    LightType type() const override { return LightType::Polygon; }
    const char* name() const override { return "polygon"; }
    bool isArea() const override { return true; }
    bool oneSided() const override { return true; }
    int sceneFormat() const override { return 4; }  // polygon lights came with format 4
    std::vector<std::string> keys() const override { return {"vertices"}; }
    void parse(const json& j, const JsonReader& r, const std::string& f,
               Light& light) const override {
        const json& jv = need(j, r, f, "vertices");
        r.requireArray(jv, f + ".vertices");
        if (jv.size() < kMinVertices || jv.size() > kMaxVertices)
            r.fail(f + ".vertices", std::to_string(jv.size()) + " vertices (a polygon light has " +
                                        std::to_string(kMinVertices) + " to " +
                                        std::to_string(kMaxVertices) + ")");
        std::vector<glm::dvec3> v;
        Bounds3d box;
        for (size_t k = 0; k < jv.size(); ++k) {
            v.push_back(r.vec3(jv[k], vertexField(f, k)));
            box.extend(v.back());
        }
        const double size = box.extent();
        const glm::dvec3 twice = twiceVectorArea(v);
        const double twiceArea = glm::length(twice);
        if (!(size > 0.0) || !std::isfinite(size) || !(twiceArea > 1e-9 * size * size))
            r.fail(f + ".vertices", "zero area (degenerate)");
        const glm::dvec3 n = twice / twiceArea;
        checkPlanar(v, n, size, r, f);
        checkConvex(v, n, r, f);
        glm::dvec3 centroid(0.0);
        for (size_t k = 1; k + 1 < v.size(); ++k) {
            const double a = glm::dot(glm::cross(v[k] - v[0], v[k + 1] - v[0]), n);
            centroid += a * (v[0] + v[k] + v[k + 1]) / 3.0;
        }
        light.wsPosition = centroid / twiceArea;
        light.wsNormal = n;
        light.wsVertices = std::move(v);
    }
    void write(const Light& l, json& j) const override {
        json vs = json::array();
        for (const glm::dvec3& p : l.wsVertices) vs.push_back(jsonVec3(p));
        j["vertices"] = vs;
    }
    glm::dvec3 wsEmitNormal(const Light& l) const override { return l.wsNormal; }
    GltfStandIn gltfStandIn(const Light& l, const Bounds3d& wsBounds) const override {
        return spotStandInAlongNormal(l, wsBounds);
    }
    void gltfExtras(const Light& l, json& j) const override {
        write(l, j);
        j["center"] = jsonVec3(l.wsPosition);
        j["normal"] = jsonVec3(l.wsNormal);
    }
    double equalAreaDiameter(const Light& l) const override {
        return 2.0 *
               std::sqrt(0.5 * glm::length(twiceVectorArea(l.wsVertices)) / glm::pi<double>());
    }
};

}  // namespace

SO_REGISTER_LIGHT_KIND(PolygonLightKind);

}  // namespace so
