// The closed forms of lambert.h against brute-force quadrature of the defining integrals, which
// shares nothing with Lambert's formula beyond the integrand.
#include "lambert.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace so::test {
namespace {

const glm::dvec3 kUp(0.0, 1.0, 0.0);
const glm::dvec3 kDown(0.0, -1.0, 0.0);

// The integrand straight from its definition (one-sided at both ends).
double geometryTerm(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& y,
                    const glm::dvec3& emitNormal) {
    const glm::dvec3 d = y - p;
    const double r2 = glm::dot(d, d);
    const double cosP = glm::dot(glm::normalize(n), d);
    const double cosY = -glm::dot(glm::normalize(emitNormal), d);
    if (cosP <= 0.0 || cosY <= 0.0) return 0.0;
    return cosP * cosY / (r2 * r2);
}

// Midpoint rule on the Duffy map (u, v) -> a + u (b - a) + u v (c - b) of the unit square onto
// triangle abc: smooth, so the error is O(1/cells^2) even where an edge is slanted, which a grid
// over a bounding box with an inside test would not give.
double numericTriangle(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& a,
                       const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& emitNormal,
                       int cells) {
    const double twiceArea = glm::length(glm::cross(b - a, c - b));
    const double h = 1.0 / cells;
    double sum = 0.0;
    for (int i = 0; i < cells; ++i) {
        const double u = (i + 0.5) * h;
        double row = 0.0;
        for (int j = 0; j < cells; ++j) {
            const double v = (j + 0.5) * h;
            row += geometryTerm(p, n, a + u * (b - a) + u * v * (c - b), emitNormal);
        }
        sum += row * u;
    }
    return sum * twiceArea * h * h;
}

// A convex polygon as a fan of triangles.
double numericPolygon(const glm::dvec3& p, const glm::dvec3& n, const std::vector<glm::dvec3>& poly,
                      const glm::dvec3& emitNormal, int cells = 1500) {
    double sum = 0.0;
    for (size_t i = 1; i + 1 < poly.size(); ++i)
        sum += numericTriangle(p, n, poly[0], poly[i], poly[i + 1], emitNormal, cells);
    return sum;
}

// The emitter side of a polygon that faces p.
glm::dvec3 normalTowards(const std::vector<glm::dvec3>& poly, const glm::dvec3& p) {
    glm::dvec3 nrm = glm::normalize(glm::cross(poly[1] - poly[0], poly[2] - poly[0]));
    return glm::dot(nrm, p - poly[0]) > 0.0 ? nrm : -nrm;
}

std::vector<glm::dvec3> reversed(std::vector<glm::dvec3> poly) {
    std::reverse(poly.begin(), poly.end());
    return poly;
}

// A regular polygon of k vertices centred at c in the plane spanned by the unit vectors u, w.
std::vector<glm::dvec3> regularPolygon(const glm::dvec3& c, const glm::dvec3& u,
                                       const glm::dvec3& w, double radius, int k) {
    std::vector<glm::dvec3> poly;
    for (int i = 0; i < k; ++i) {
        const double a = 2.0 * std::numbers::pi * i / k + 0.3;
        poly.push_back(c + radius * (std::cos(a) * u + std::sin(a) * w));
    }
    return poly;
}

// Checks the closed form against quadrature, for both windings.
void expectMatchesNumeric(const glm::dvec3& p, const glm::dvec3& n,
                          const std::vector<glm::dvec3>& poly, const glm::dvec3& emitNormal) {
    const double exact = polygonIrradiance(p, n, poly, emitNormal);
    const double numeric = numericPolygon(p, n, poly, emitNormal);
    ASSERT_GT(numeric, 0.0);
    EXPECT_LT(std::fabs(exact - numeric) / numeric, 1e-4)
        << "exact " << exact << " numeric " << numeric;
    EXPECT_NEAR(polygonIrradiance(p, n, reversed(poly), emitNormal), exact, 1e-14 * exact);
}

TEST(Lambert, PolygonSquareStraightAbove) {
    const AxisRect sq{1.0, -0.5, 0.5, -0.5, 0.5};
    expectMatchesNumeric({0, 0, 0}, kUp, axisRectPolygon(sq), kDown);
}

TEST(Lambert, PolygonSquareOffset) {
    const AxisRect sq{1.5, 0.7, 1.9, -0.4, 0.6};
    expectMatchesNumeric({-0.3, 0.2, 0.1}, kUp, axisRectPolygon(sq), kDown);
}

TEST(Lambert, PolygonTiltedReceiver) {
    const AxisRect sq{1.0, -0.5, 0.5, -0.5, 0.5};
    // Tilted but with the whole square still above the horizon (no clipping).
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.4, 1.0, -0.25));
    const std::vector<glm::dvec3> poly = axisRectPolygon(sq);
    for (const glm::dvec3& v : poly) ASSERT_GT(glm::dot(n, v), 0.0);
    expectMatchesNumeric({0, 0, 0}, n, poly, kDown);
}

TEST(Lambert, PolygonPartlyBelowHorizon) {
    const AxisRect sq{1.0, -2.0, 1.0, -0.8, 1.2};
    const glm::dvec3 p(0.0, 0.0, 0.0);
    const glm::dvec3 n = glm::normalize(glm::dvec3(1.0, 1.0, 0.3));
    const std::vector<glm::dvec3> poly = axisRectPolygon(sq);
    int below = 0;
    for (const glm::dvec3& v : poly) below += glm::dot(n, v - p) < 0.0;
    ASSERT_GT(below, 0);  // the clipping path is what this test is for
    ASSERT_LT(below, 4);
    expectMatchesNumeric(p, n, poly, kDown);
}

TEST(Lambert, PolygonLargeAndClose) {
    // Edges subtending more than 90 degrees from p, where an angle from asin(|cross|) or a
    // clamped acos would go wrong.
    const AxisRect strip{0.3, -1.0, 1.0, -0.3, 0.3};
    const glm::dvec3 p(0.05, 0.0, 0.02);
    const std::vector<glm::dvec3> poly = axisRectPolygon(strip);
    ASSERT_LT(glm::dot(poly[1] - p, poly[2] - p), 0.0);
    expectMatchesNumeric(p, kUp, poly, kDown);
}

TEST(Lambert, PolygonBehindEmitterOrBelowHorizonIsZero) {
    const std::vector<glm::dvec3> sq = axisRectPolygon({1.0, -0.5, 0.5, -0.5, 0.5});
    // Behind a downward emitter, then in its plane.
    EXPECT_EQ(polygonIrradiance({0.0, 2.0, 0.0}, kDown, sq, kDown), 0.0);
    EXPECT_EQ(polygonIrradiance({3.0, 1.0, 0.0}, {-1.0, 0.0, 0.0}, sq, kDown), 0.0);
    // Facing away from the light.
    EXPECT_EQ(polygonIrradiance({0.0, 0.0, 0.0}, kDown, sq, kDown), 0.0);
    // The same configurations with the emitter or receiver turned round do receive light, so the
    // zeros above come from the one-sidedness and not from a broken formula.
    EXPECT_GT(polygonIrradiance({0.0, 2.0, 0.0}, kDown, sq, kUp), 0.1);
    EXPECT_GT(polygonIrradiance({0.0, 0.0, 0.0}, kUp, sq, kDown), 0.1);
    // Degenerate input.
    EXPECT_EQ(polygonIrradiance({0.0, 0.0, 0.0}, kUp, {sq[0], sq[1]}, kDown), 0.0);
    EXPECT_EQ(polygonIrradiance({0.0, 0.0, 0.0}, kUp, {sq[0], sq[1], sq[1]}, kDown), 0.0);
}

TEST(Lambert, PolygonTriangle) {
    const glm::dvec3 p(0.1, 0.0, 0.05);
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 1.0, -0.1));
    const std::vector<glm::dvec3> tri = {{0.3, 1.2, -0.4}, {1.5, 2.0, 0.1}, {-0.2, 1.8, 0.9}};
    expectMatchesNumeric(p, n, tri, normalTowards(tri, p));
}

TEST(Lambert, PolygonPentagon) {
    const glm::dvec3 u = glm::normalize(glm::dvec3(1.0, 0.3, 0.0));
    const glm::dvec3 w = glm::normalize(glm::cross(u, glm::dvec3(0.2, 0.1, 1.0)));
    const std::vector<glm::dvec3> pent = regularPolygon({0.5, 1.5, -0.3}, u, w, 0.8, 5);
    const glm::dvec3 p(0.0, 0.0, 0.0);
    expectMatchesNumeric(p, kUp, pent, normalTowards(pent, p));
    // Tilted so the horizon cuts the pentagon.
    const glm::dvec3 n = glm::normalize(glm::dvec3(-1.0, 0.5, 0.2));
    int below = 0;
    for (const glm::dvec3& v : pent) below += glm::dot(n, v - p) < 0.0;
    ASSERT_GT(below, 0);
    ASSERT_LT(below, 5);
    expectMatchesNumeric(p, n, pent, normalTowards(pent, p));
}

TEST(Lambert, PolygonIsAdditive) {
    // Integrals over two halves sum to the whole: catches a sign or orientation slip that a
    // single comparison with quadrature at a symmetric point could miss.
    const glm::dvec3 p(0.4, 0.1, -0.2);
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.7, 1.0, 0.1));
    const AxisRect whole{2.0, -1.0, 1.5, -0.7, 0.9};
    AxisRect left = whole, right = whole;
    left.x1 = right.x0 = 0.3;
    const double sum = polygonIrradiance(p, n, axisRectPolygon(left), kDown) +
                       polygonIrradiance(p, n, reversed(axisRectPolygon(right)), kDown);
    EXPECT_NEAR(sum, polygonIrradiance(p, n, axisRectPolygon(whole), kDown), 1e-14);
}

// ----- Rectangle light behind a rectangle occluder -----

// Whether the open segment p -> y crosses the open occluder rectangle.
bool blocked(const glm::dvec3& p, const glm::dvec3& y, const AxisRect& occ) {
    const double dy = y.y - p.y;
    if (dy == 0.0) return false;
    const double t = (occ.y - p.y) / dy;
    if (!(t > 0.0 && t < 1.0)) return false;
    const glm::dvec3 q = p + t * (y - p);
    return q.x > occ.x0 && q.x < occ.x1 && q.z > occ.z0 && q.z < occ.z1;
}

struct Quadrature {
    double visible = 0.0;  // int v G dA
    double total = 0.0;    // int G dA
    double visibleArea = 0.0;
    double area = 0.0;
};

// The midpoint rule on a cells x cells grid over the light. A cell whose corners disagree about
// visibility holds a shadow edge, where one midpoint test would be off by up to half a cell's
// weight; such cells get a refine x refine grid of their own, which keeps the quadrature error of
// V within ~4e-5 (a 32nd of a cell) where plain midpoints at 1500 cells were off by up to 2.4e-4.
Quadrature numericOccluded(const glm::dvec3& p, const glm::dvec3& n, const AxisRect& light,
                           const AxisRect& occ, int cells = 1500, int refine = 16) {
    const double hx = (light.x1 - light.x0) / cells, hz = (light.z1 - light.z0) / cells;
    auto point = [&](double i, double j) {
        return glm::dvec3(light.x0 + i * hx, light.y, light.z0 + j * hz);
    };
    std::vector<char> corner(static_cast<size_t>(cells + 1) * (cells + 1));
    for (int i = 0; i <= cells; ++i)
        for (int j = 0; j <= cells; ++j) corner[i * (cells + 1) + j] = blocked(p, point(i, j), occ);
    Quadrature q;
    for (int i = 0; i < cells; ++i) {
        for (int j = 0; j < cells; ++j) {
            const char c00 = corner[i * (cells + 1) + j], c01 = corner[i * (cells + 1) + j + 1];
            const char c10 = corner[(i + 1) * (cells + 1) + j];
            const char c11 = corner[(i + 1) * (cells + 1) + j + 1];
            const int sub = (c00 == c01 && c00 == c10 && c00 == c11) ? 1 : refine;
            const double cellArea = hx * hz / (sub * sub);
            for (int a = 0; a < sub; ++a) {
                for (int b = 0; b < sub; ++b) {
                    const glm::dvec3 y = point(i + (a + 0.5) / sub, j + (b + 0.5) / sub);
                    const double g = geometryTerm(p, n, y, kDown) * cellArea;
                    const bool v = !blocked(p, y, occ);
                    q.total += g;
                    q.area += cellArea;
                    if (v) {
                        q.visible += g;
                        q.visibleArea += cellArea;
                    }
                }
            }
        }
    }
    return q;
}

// How many edges of the occluder's shadow on the light's plane pass through the light's interior:
// 1 = the shadow covers one edge of the light, 2 = a corner or a band across it, 4 = inside it.
int shadowEdgesInsideLight(const glm::dvec3& p, const AxisRect& light, const AxisRect& occ) {
    const double s = (light.y - p.y) / (occ.y - p.y);
    const double x0 = p.x + (occ.x0 - p.x) * s, x1 = p.x + (occ.x1 - p.x) * s;
    const double z0 = p.z + (occ.z0 - p.z) * s, z1 = p.z + (occ.z1 - p.z) * s;
    const bool xOverlap = x0 < light.x1 && x1 > light.x0;
    const bool zOverlap = z0 < light.z1 && z1 > light.z0;
    if (!xOverlap || !zOverlap) return 0;
    auto inside = [](double v, double lo, double hi) { return v > lo && v < hi; };
    return inside(x0, light.x0, light.x1) + inside(x1, light.x0, light.x1) +
           inside(z0, light.z0, light.z1) + inside(z1, light.z0, light.z1);
}

// The layout of the square-occluder test scene (occluder y = 2) with a unit light at y = 4, so
// the occluder's shadow on the light plane is it scaled by 2 about a receiver point on y = 0.
const AxisRect kLight{4.0, -0.5, 0.5, -0.5, 0.5};
const AxisRect kOccluder{2.0, -1.5, 1.0, -1.0, 1.25};

TEST(Lambert, RectOccluderUmbraIsExactlyZero) {
    for (const glm::dvec3& p :
         {glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(-1.2, 0.0, 0.5), glm::dvec3(0.4, 0.3, -0.3)}) {
        EXPECT_EQ(exactRectLightRectOccluderV(p, kUp, kLight, kOccluder), 0.0);
        EXPECT_EQ(exactRectLightUnweightedFraction(p, kUp, kLight, kOccluder), 0.0);
        EXPECT_EQ(numericOccluded(p, kUp, kLight, kOccluder, 200).visible, 0.0);
    }
}

TEST(Lambert, RectOccluderFullyLitIsExactlyOne) {
    // Outside the penumbra, then at and above the occluder's plane (which it cannot block from).
    for (const glm::dvec3& p :
         {glm::dvec3(3.0, 0.0, 0.0), glm::dvec3(0.0, 0.0, 5.0), glm::dvec3(-4.0, 0.0, -3.0),
          glm::dvec3(0.0, 2.0, 0.0), glm::dvec3(0.2, 3.0, -0.1)}) {
        EXPECT_EQ(exactRectLightRectOccluderV(p, kUp, kLight, kOccluder), 1.0);
        EXPECT_EQ(exactRectLightUnweightedFraction(p, kUp, kLight, kOccluder), 1.0);
        const Quadrature q = numericOccluded(p, kUp, kLight, kOccluder, 200);
        EXPECT_EQ(q.visible, q.total);
    }
}

TEST(Lambert, RectOccluderNoLightAboveHorizonIsZero) {
    // The light entirely below the receiver's horizon, and p above the light (behind the emitter):
    // the denominator vanishes and the oracle's convention is V = 0.
    const glm::dvec3 sideways = glm::normalize(glm::dvec3(1.0, -0.1, 0.0));
    EXPECT_EQ(exactRectLightRectOccluderV({3.0, 0.0, 0.0}, sideways, kLight, kOccluder), 0.0);
    EXPECT_EQ(exactRectLightRectOccluderV({0.0, 5.0, 0.0}, kDown, kLight, kOccluder), 0.0);
    EXPECT_EQ(exactRectLightUnweightedFraction({3.0, 0.0, 0.0}, sideways, kLight, kOccluder), 0.0);
}

struct PenumbraCase {
    glm::dvec3 p;
    glm::dvec3 n;
    AxisRect light;
    AxisRect occluder;
    int shadowEdges;  // expected from shadowEdgesInsideLight: the configuration the case covers
};

// A light four times the size of a small occluder, so the shadow can fall inside it.
const AxisRect kBigLight{4.0, -1.0, 1.0, -1.0, 1.0};
const AxisRect kSmallOccluder{2.0, -0.1, 0.1, -0.15, 0.1};
// A slat across the whole light: its shadow is a band over two opposite edges.
const AxisRect kSlat{2.0, -0.1, 0.1, -5.0, 5.0};

std::vector<PenumbraCase> penumbraCases() {
    const glm::dvec3 tilted = glm::normalize(glm::dvec3(1.0, 0.4, 0.3));
    const glm::dvec3 steeper = glm::normalize(glm::dvec3(1.0, 0.6, 0.3));
    return {
        {{1.8, 0.0, 0.0}, kUp, kLight, kOccluder, 1},
        {{2.3, 0.0, 0.1}, kUp, kLight, kOccluder, 1},
        {{1.6, 0.0, -0.2}, kUp, kLight, kOccluder, 1},
        {{0.3, 0.0, 2.1}, kUp, kLight, kOccluder, 1},
        {{-3.2, 0.0, 0.0}, kUp, kLight, kOccluder, 1},
        {{1.8, 0.0, 2.2}, kUp, kLight, kOccluder, 2},
        {{2.2, 0.0, 2.3}, kUp, kLight, kOccluder, 2},
        {{-3.3, 0.0, -2.2}, kUp, kLight, kOccluder, 2},
        {{1.8, 0.5, 0.3}, kUp, kLight, kOccluder, 1},   // receiver off y = 0
        {{1.06, 1.8, 0.0}, kUp, kLight, kOccluder, 1},  // just under the occluder: s = 11
        {{0.2, 0.0, -0.1}, kUp, kBigLight, kSmallOccluder, 4},
        {{-0.2, 0.7, 0.3}, kUp, kBigLight, kSmallOccluder, 4},
        {{0.3, 0.0, 0.0}, kUp, kBigLight, kSlat, 2},
        // Tilted receiver whose horizon cuts the light across the visible part.
        {{1.7, 0.0, 0.2}, tilted, kLight, kOccluder, 1},
        {{1.6, 0.0, 2.2}, steeper, kLight, kOccluder, 2},
    };
}

TEST(Lambert, RectOccluderPenumbraMatchesQuadrature) {
    // Off the quadrature grid lines: the cases' round coordinates put shadow edges on them, where
    // the midpoint rule is exact by coincidence and would not test the refinement.
    const glm::dvec3 offGrid(0.00731, 0.0, -0.00417);
    for (PenumbraCase c : penumbraCases()) {
        c.p += offGrid;
        SCOPED_TRACE(testing::Message()
                     << "p = (" << c.p.x << ", " << c.p.y << ", " << c.p.z << "), n = (" << c.n.x
                     << ", " << c.n.y << ", " << c.n.z << ")");
        ASSERT_EQ(shadowEdgesInsideLight(c.p, c.light, c.occluder), c.shadowEdges);
        const Quadrature q = numericOccluded(c.p, c.n, c.light, c.occluder);
        const double v = exactRectLightRectOccluderV(c.p, c.n, c.light, c.occluder);
        const double numericV = q.visible / q.total;
        // A genuine penumbra point, not one that 0 or 1 would pass.
        EXPECT_GT(numericV, 0.01);
        EXPECT_LT(numericV, 0.99);
        EXPECT_NEAR(v, numericV, 2e-4);
        EXPECT_NEAR(exactRectLightUnweightedFraction(c.p, c.n, c.light, c.occluder),
                    q.visibleArea / q.area, 2e-4);
    }
}

TEST(Lambert, RectOccluderTiltedReceiverClipsTheVisiblePart) {
    // The tilted cases above only test clipping if the horizon really crosses the light there.
    const glm::dvec3 tilted = glm::normalize(glm::dvec3(1.0, 0.4, 0.3));
    const glm::dvec3 p(1.7, 0.0, 0.2);
    int below = 0;
    for (const glm::dvec3& y : axisRectPolygon(kLight)) below += glm::dot(tilted, y - p) < 0.0;
    ASSERT_GT(below, 0);
    ASSERT_LT(below, 4);
    // Weighting matters here: the horizon removes mostly blocked light, so V > the area fraction.
    EXPECT_GT(exactRectLightRectOccluderV(p, tilted, kLight, kOccluder),
              exactRectLightUnweightedFraction(p, tilted, kLight, kOccluder) + 0.05);
}

TEST(Lambert, TinyLightApproachesHardShadow) {
    const glm::dvec3 centre(0.3, 4.0, 0.2);
    const double half = 0.5e-3;
    const AxisRect tiny{centre.y, centre.x - half, centre.x + half, centre.z - half,
                        centre.z + half};
    // On this plane the penumbra is 1e-3 wide (w (d_r - d_b) / d_b with d_r = 4, d_b = 2).
    const double penumbra = 1e-3;
    int checked = 0;
    for (int i = -40; i <= 40; ++i) {
        for (int j = -40; j <= 40; ++j) {
            const glm::dvec3 p(i * 0.1 + 0.013, 0.0, j * 0.1 - 0.021);
            // Distance from p to the hard shadow's outline on the receiver plane.
            const double sx0 = 2.0 * kOccluder.x0 - centre.x, sx1 = 2.0 * kOccluder.x1 - centre.x;
            const double sz0 = 2.0 * kOccluder.z0 - centre.z, sz1 = 2.0 * kOccluder.z1 - centre.z;
            const double margin = std::min({std::fabs(p.x - sx0), std::fabs(p.x - sx1),
                                            std::fabs(p.z - sz0), std::fabs(p.z - sz1)});
            if (margin < penumbra) continue;
            const double hard = blocked(p, centre, kOccluder) ? 0.0 : 1.0;
            EXPECT_EQ(exactRectLightRectOccluderV(p, kUp, tiny, kOccluder), hard)
                << "p = (" << p.x << ", " << p.z << ")";
            ++checked;
        }
    }
    EXPECT_GT(checked, 6000);
    // On the hard shadow's edge half of the light is hidden, and G is nearly constant over it.
    const glm::dvec3 onEdge(2.0 * kOccluder.x1 - centre.x, 0.0, 0.0);
    EXPECT_NEAR(exactRectLightRectOccluderV(onEdge, kUp, tiny, kOccluder), 0.5, 1e-3);
    // Midway through the penumbra of a larger light V is further from the hard answer, and
    // converges to it as the light shrinks.
    const glm::dvec3 nearEdge = onEdge + glm::dvec3(0.2e-3, 0.0, 0.0);
    double previous = 1.0;
    for (double size : {1e-1, 1e-2, 1e-3, 1e-4}) {
        const AxisRect l{centre.y, centre.x - size / 2, centre.x + size / 2, centre.z - size / 2,
                         centre.z + size / 2};
        const double gap = 1.0 - exactRectLightRectOccluderV(nearEdge, kUp, l, kOccluder);
        EXPECT_LE(gap, previous);
        previous = gap;
    }
    EXPECT_EQ(previous, 0.0);
}

}  // namespace
}  // namespace so::test
