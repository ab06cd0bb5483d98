// The lightmap's atlas on its own, without GL (raster_compare/gl/lightmaps/lightmap_atlas.h):
// coplanar connected triangles share a chart of exactly their size, a curved mesh gets one chart
// per triangle, a fold is split, TEXCOORD_1 is kept and scaled to the density; and in every atlas
// no two triangles cover one texel centre, every triangle lies inside its chart, every chart inside
// the atlas with its padding clear of the others, and the same input gives the same atlas.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "raster_compare/gl/lightmaps/lightmap_atlas.h"

namespace so {
namespace {

// An n x n grid of quads (two triangles each) spanning [x0, x0 + size] x [z0, z0 + size] at y = 0,
// shared vertices, wound to face +y.
MeshPrimitive grid(double x0, double z0, double size, int n) {
    MeshPrimitive m;
    m.name = "grid";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.wsPositions.push_back({x0 + size * i / n, 0.0, z0 + size * j / n});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1),
                           d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    return m;
}

// An axis-aligned box, each face two triangles with its own four vertices, wound outwards.
MeshPrimitive box(const glm::dvec3& lo, const glm::dvec3& hi) {
    MeshPrimitive m;
    m.name = "box";
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const uint32_t base = uint32_t(m.wsPositions.size());
            for (int k = 0; k < 4; ++k) {
                glm::dvec3 p;
                p[axis] = side ? hi[axis] : lo[axis];
                p[u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                p[v] = (k >= 2) ? hi[v] : lo[v];
                m.wsPositions.push_back(p);
            }
            if (side)
                m.indices.insert(m.indices.end(),
                                 {base, base + 1, base + 2, base, base + 2, base + 3});
            else
                m.indices.insert(m.indices.end(),
                                 {base, base + 2, base + 1, base, base + 3, base + 2});
        }
    return m;
}

// A band of a cylinder (radius 1, height 1) in `n` facets: no two triangles coplanar but the two
// of a facet.
MeshPrimitive cylinderBand(int n) {
    MeshPrimitive m;
    m.name = "band";
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        m.wsPositions.push_back({std::cos(a), 0.0, std::sin(a)});
        m.wsPositions.push_back({std::cos(a), 1.0, std::sin(a)});
    }
    for (int i = 0; i < n; ++i) {
        const uint32_t a = uint32_t(2 * i), b = a + 1, c = uint32_t(2 * ((i + 1) % n)), d = c + 1;
        // Each facet's two triangles bent apart: the second one's far corner lifted off the plane.
        m.indices.insert(m.indices.end(), {a, b, c, c, b, d});
    }
    for (size_t v = 1; v < m.wsPositions.size(); v += 4)
        m.wsPositions[v] *= glm::dvec3(1.1, 1, 1.1);
    return m;
}

// A fan in the plane y = 0 that winds twice around its centre: consistently oriented, every
// triangle coplanar and connected to the next across a shared edge, and triangles 4 and 5 over 0
// and 1. One chart would overlap itself.
MeshPrimitive doubleFan() {
    MeshPrimitive m;
    m.name = "fan";
    m.wsPositions.push_back({0, 0, 0});
    for (int k = 0; k <= 6; ++k) {
        const double a = -0.5 * std::numbers::pi * k, r = 1.0 + 0.25 * k;
        m.wsPositions.push_back({r * std::cos(a), 0.0, r * std::sin(a)});
    }
    for (uint32_t k = 0; k < 6; ++k) m.indices.insert(m.indices.end(), {0, k + 1, k + 2});
    return m;
}

Scene sceneOf(std::vector<MeshPrimitive> meshes) {
    Scene s;
    s.meshes = std::move(meshes);
    finalizeScene(s);
    return s;
}

// Strictly inside, with a margin in texels (a centre on a shared edge belongs to neither here).
bool strictlyInside(const std::array<glm::dvec2, 3>& t, const glm::dvec2& p) {
    auto edge = [](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& q) {
        return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
    };
    const double e0 = edge(t[0], t[1], p), e1 = edge(t[1], t[2], p), e2 = edge(t[2], t[0], p);
    const double eps = 1e-9;
    return (e0 > eps && e1 > eps && e2 > eps) || (e0 < -eps && e1 < -eps && e2 < -eps);
}

// The invariants every atlas keeps (the header's promise).
void expectWellFormed(const Scene& scene, const LightmapAtlas& atlas, int padding) {
    ASSERT_GT(atlas.width, 0);
    ASSERT_GT(atlas.height, 0);
    for (size_t i = 0; i < atlas.charts.size(); ++i) {
        const AtlasChart& a = atlas.charts[i];
        EXPECT_GE(a.x, padding);
        EXPECT_GE(a.y, padding);
        EXPECT_LE(a.x + a.width + padding, atlas.width);
        EXPECT_LE(a.y + a.height + padding, atlas.height);
        for (size_t j = i + 1; j < atlas.charts.size(); ++j) {
            const AtlasChart& b = atlas.charts[j];
            // At least 2 x padding texels between any two charts.
            const bool apart =
                a.x + a.width + 2 * padding <= b.x || b.x + b.width + 2 * padding <= a.x ||
                a.y + a.height + 2 * padding <= b.y || b.y + b.height + 2 * padding <= a.y;
            EXPECT_TRUE(apart) << "charts " << i << " and " << j;
        }
    }
    std::vector<uint8_t> cover(atlas.texels(), 0);
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi)
        for (size_t t = 0; t < scene.meshes[mi].triangleCount(); ++t) {
            const int32_t c = atlas.chartOf[mi][t];
            if (c < 0) continue;
            const AtlasChart& chart = atlas.charts[size_t(c)];
            EXPECT_EQ(chart.mesh, mi);
            const auto& tri = atlas.corners[mi][t];
            for (const glm::dvec2& p : tri) {
                EXPECT_GE(p.x, chart.x - 1e-6);
                EXPECT_LE(p.x, chart.x + chart.width + 1e-6);
                EXPECT_GE(p.y, chart.y - 1e-6);
                EXPECT_LE(p.y, chart.y + chart.height + 1e-6);
            }
            for (int y = chart.y; y < chart.y + chart.height; ++y)
                for (int x = chart.x; x < chart.x + chart.width; ++x)
                    if (strictlyInside(tri, {x + 0.5, y + 0.5})) {
                        EXPECT_EQ(++cover[size_t(y) * size_t(atlas.width) + size_t(x)], 1)
                            << "texel (" << x << ", " << y << ") covered twice";
                    }
        }
}

TEST(LightmapAtlas, CoplanarTrianglesShareAChartOfExactlyTheirSize) {
    const Scene s = sceneOf({grid(-2, -2, 4, 8), box({0, 0, 0}, {2, 1.5, 1})});
    AtlasSettings settings;
    settings.texelsPerUnit = 16;
    settings.padding = 2;
    const LightmapAtlas atlas = buildLightmapAtlas(s, settings);
    ASSERT_EQ(atlas.charts.size(), 1u + 6u) << "the grid, and one chart per face of the box";
    EXPECT_EQ(atlas.charts[0].triangles.size(), 128u);
    EXPECT_EQ(atlas.charts[0].width, 64);
    EXPECT_EQ(atlas.charts[0].height, 64);
    // The box's faces: 2 x 1.5, 2 x 1 and 1.5 x 1 units, twice each, at 16 texels a unit.
    std::vector<std::pair<int, int>> faces;
    for (size_t c = 1; c < 7; ++c) {
        EXPECT_EQ(atlas.charts[c].triangles.size(), 2u);
        const int w = atlas.charts[c].width, h = atlas.charts[c].height;
        faces.push_back({std::min(w, h), std::max(w, h)});
    }
    std::sort(faces.begin(), faces.end());
    const std::vector<std::pair<int, int>> expected = {{16, 24}, {16, 24}, {16, 32},
                                                       {16, 32}, {24, 32}, {24, 32}};
    EXPECT_EQ(faces, expected);
    EXPECT_EQ(atlas.bakedTriangles, 128u + 12u);
    expectWellFormed(s, atlas, settings.padding);
}

TEST(LightmapAtlas, ACurvedMeshGetsOneChartPerFacetAndAFoldIsSplit) {
    const Scene s = sceneOf({cylinderBand(12), doubleFan()});
    AtlasSettings settings;
    settings.texelsPerUnit = 24;
    const LightmapAtlas atlas = buildLightmapAtlas(s, settings);
    size_t bandCharts = 0, fanCharts = 0;
    for (const AtlasChart& c : atlas.charts) (c.mesh == 0 ? bandCharts : fanCharts) += 1;
    EXPECT_EQ(bandCharts, 24u) << "no two triangles of the band are coplanar";
    EXPECT_GE(fanCharts, 2u) << "the fan overlaps itself in one chart";
    EXPECT_LE(fanCharts, 3u);
    expectWellFormed(s, atlas, settings.padding);
}

// TEXCOORD_1 is kept: one chart over its bounds, scaled so that the mesh's texels per unit of
// surface are the density's: a 2 x 2 quad mapped to [0, 1]^2 at 16 texels a unit is 32 x 32.
TEST(LightmapAtlas, Texcoord1IsKeptAndScaledToTheDensity) {
    MeshPrimitive quad = grid(0, 0, 2, 1);
    quad.lightmapUvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    const Scene s = sceneOf({quad, box({3, 0, 0}, {4, 1, 1})});
    AtlasSettings settings;
    settings.texelsPerUnit = 16;
    settings.padding = 3;
    const LightmapAtlas atlas = buildLightmapAtlas(s, settings);
    EXPECT_EQ(atlas.texcoord1Meshes, 1u);
    const AtlasChart& chart = atlas.charts[size_t(atlas.chartOf[0][0])];
    EXPECT_TRUE(chart.fromTexcoord1);
    EXPECT_EQ(chart.width, 32);
    EXPECT_EQ(chart.height, 32);
    for (size_t t = 0; t < 2; ++t)
        for (size_t k = 0; k < 3; ++k) {
            const glm::dvec2 uv = s.meshes[0].lightmapUvs[s.meshes[0].indices[3 * t + k]];
            EXPECT_EQ(atlas.corners[0][t][k], glm::dvec2(chart.x, chart.y) + 32.0 * uv);
        }
    expectWellFormed(s, atlas, settings.padding);
    MeshPrimitive flat = quad;
    flat.lightmapUvs = {{0, 0}, {1, 0}, {0, 0}, {1, 0}};
    try {
        buildLightmapAtlas(sceneOf({flat}), settings);
        ADD_FAILURE() << "TEXCOORD_1 of no area accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("TEXCOORD_1"), std::string::npos) << e.what();
    }
}

// Dynamic meshes are left out and counted; the same input gives the same atlas.
TEST(LightmapAtlas, DynamicMeshesAreLeftOutAndTheLayoutIsDeterministic) {
    MeshPrimitive moving = box({-0.5, 0.5, -0.5}, {0.5, 1.5, 0.5});
    moving.dynamic = true;
    const Scene s = sceneOf({grid(-2, -2, 4, 4), moving, cylinderBand(8)});
    AtlasSettings settings;
    settings.texelsPerUnit = 10;
    const LightmapAtlas a = buildLightmapAtlas(s, settings), b = buildLightmapAtlas(s, settings);
    EXPECT_EQ(a.dynamicMeshes, 1u);
    EXPECT_EQ(a.dynamicTriangles, 12u);
    EXPECT_TRUE(
        std::all_of(a.chartOf[1].begin(), a.chartOf[1].end(), [](int32_t c) { return c < 0; }));
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    ASSERT_EQ(a.charts.size(), b.charts.size());
    for (size_t c = 0; c < a.charts.size(); ++c) {
        EXPECT_EQ(a.charts[c].x, b.charts[c].x);
        EXPECT_EQ(a.charts[c].y, b.charts[c].y);
        EXPECT_EQ(a.charts[c].triangles, b.charts[c].triangles);
    }
    EXPECT_EQ(a.corners, b.corners);
    expectWellFormed(s, a, settings.padding);
}

// The atlas is bounded: density times area beyond 2^24 texels, or a chart wider than the atlas's
// side, is an input error naming texels_per_unit, before anything is allocated for it.
TEST(LightmapAtlas, DensityBeyondTheLimitNamesTheParameter) {
    const Scene s = sceneOf({grid(-500, -500, 1000, 2)});
    AtlasSettings settings;
    settings.texelsPerUnit = 8;  // 1000^2 * 64 texels
    for (double d : {8.0, 4.2}) {
        settings.texelsPerUnit = d;
        try {
            buildLightmapAtlas(s, settings);
            ADD_FAILURE() << "an atlas over the limit at " << d;
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find("technique lightmap: texels_per_unit:"), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
    settings.texelsPerUnit = 4;  // 4000 x 4000 texels: within both limits
    const LightmapAtlas atlas = buildLightmapAtlas(s, settings);
    EXPECT_LE(atlas.texels(), kMaxAtlasTexels);
}

}  // namespace
}  // namespace so
