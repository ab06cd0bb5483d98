#include "raster_compare/gl/lightmaps/lightmap_atlas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace so {

namespace {

// Triangles that share an edge are coplanar when their unit normals' cosine is at least this
// (about 0.06 degrees): what float vertex coordinates of one plane stay within.
constexpr double kCoplanarCos = 1.0 - 5e-7;
// A triangle whose bounds cover more grid cells than this is checked against every triangle of
// its chart instead of being put in the cells.
constexpr size_t kMaxCellsPerTriangle = 256;

// A number as a person writes it: 256, 0.5, 1024.25.
std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// A triangle projected onto its chart's plane (world units).
struct Tri2 {
    std::array<glm::dvec2, 3> p;
};

// Whether two triangles' interiors overlap (separating axes; triangles that only touch along an
// edge or at a corner, within eps, do not).
bool interiorsOverlap(const Tri2& a, const Tri2& b, double eps) {
    for (const Tri2* t : {&a, &b})
        for (int e = 0; e < 3; ++e) {
            const glm::dvec2 d = t->p[size_t((e + 1) % 3)] - t->p[size_t(e)];
            const double len = glm::length(d);
            if (!(len > 0.0)) continue;
            const glm::dvec2 axis = glm::dvec2(-d.y, d.x) / len;
            double aLo = std::numeric_limits<double>::infinity(), aHi = -aLo, bLo = aLo, bHi = -aLo;
            for (size_t k = 0; k < 3; ++k) {
                const double pa = glm::dot(axis, a.p[k]), pb = glm::dot(axis, b.p[k]);
                aLo = std::min(aLo, pa), aHi = std::max(aHi, pa);
                bLo = std::min(bLo, pb), bHi = std::max(bHi, pb);
            }
            if (aHi <= bLo + eps || bHi <= aLo + eps) return false;
        }
    return true;
}

// The triangles of one chart in a uniform grid, so that a candidate is tested against its
// neighbours only.
class OverlapGrid {
  public:
    explicit OverlapGrid(double cell) : cell_(cell), eps_(1e-9 * cell) {}

    bool overlaps(const Tri2& t) {
        ++stamp_;
        auto test = [&](uint32_t id) {
            if (seen_[id] == stamp_) return false;
            seen_[id] = stamp_;
            return interiorsOverlap(tris_[id], t, eps_);
        };
        for (uint32_t id : big_)
            if (test(id)) return true;
        std::vector<uint64_t> keys;
        if (!cellsOf(t, keys)) {
            for (uint32_t id = 0; id < tris_.size(); ++id)
                if (test(id)) return true;
            return false;
        }
        for (uint64_t key : keys) {
            const auto it = cells_.find(key);
            if (it == cells_.end()) continue;
            for (uint32_t id : it->second)
                if (test(id)) return true;
        }
        return false;
    }

    void add(const Tri2& t) {
        const uint32_t id = uint32_t(tris_.size());
        tris_.push_back(t);
        seen_.push_back(0);
        std::vector<uint64_t> keys;
        if (!cellsOf(t, keys)) {
            big_.push_back(id);
            return;
        }
        for (uint64_t key : keys) cells_[key].push_back(id);
    }

  private:
    // The cells the triangle's bounds cover, or false when they are too many.
    bool cellsOf(const Tri2& t, std::vector<uint64_t>& keys) const {
        glm::dvec2 lo = t.p[0], hi = t.p[0];
        for (const glm::dvec2& p : t.p) lo = glm::min(lo, p), hi = glm::max(hi, p);
        auto cell = [&](double v) { return int64_t(std::clamp(std::floor(v / cell_), -1e9, 1e9)); };
        const int64_t x0 = cell(lo.x), x1 = cell(hi.x), y0 = cell(lo.y), y1 = cell(hi.y);
        if (uint64_t(x1 - x0 + 1) * uint64_t(y1 - y0 + 1) > kMaxCellsPerTriangle) return false;
        for (int64_t y = y0; y <= y1; ++y)
            for (int64_t x = x0; x <= x1; ++x)
                keys.push_back(uint64_t(uint32_t(int32_t(x))) << 32 | uint32_t(int32_t(y)));
        return true;
    }

    double cell_, eps_;
    std::vector<Tri2> tris_;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
    std::vector<uint32_t> big_;
    std::vector<uint32_t> seen_;
    uint32_t stamp_ = 0;
};

// A mesh's triangles as the chart builder needs them: corners welded by position (a mesh may
// repeat a vertex per face), unit normals and whether each has an area.
struct MeshTopology {
    std::vector<std::array<uint32_t, 3>> corners;  // welded vertex ids
    std::vector<glm::dvec3> normals;
    std::vector<uint8_t> degenerate;
    // Undirected edge (lower id << 32 | higher id) -> the triangles that have it.
    std::unordered_map<uint64_t, std::vector<uint32_t>> edges;

    static uint64_t key(uint32_t a, uint32_t b) {
        return uint64_t(std::min(a, b)) << 32 | std::max(a, b);
    }
    // Whether triangle n has the directed edge a -> b.
    bool hasDirected(uint32_t n, uint32_t a, uint32_t b) const {
        for (size_t e = 0; e < 3; ++e)
            if (corners[n][e] == a && corners[n][(e + 1) % 3] == b) return true;
        return false;
    }
};

MeshTopology topologyOf(const MeshPrimitive& m) {
    MeshTopology t;
    std::map<std::array<double, 3>, uint32_t> ids;
    std::vector<uint32_t> welded(m.wsPositions.size());
    for (size_t v = 0; v < m.wsPositions.size(); ++v) {
        const glm::dvec3& p = m.wsPositions[v];
        welded[v] =
            ids.emplace(std::array<double, 3>{p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
    }
    const size_t n = m.triangleCount();
    t.corners.resize(n);
    t.normals.resize(n);
    t.degenerate.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 &a = m.wsPositions[m.indices[3 * i]],
                         &b = m.wsPositions[m.indices[3 * i + 1]],
                         &c = m.wsPositions[m.indices[3 * i + 2]];
        const glm::dvec3 cross = glm::cross(b - a, c - a);
        const double len = glm::length(cross);
        t.degenerate[i] = !(len > 0.0) || !std::isfinite(len);
        t.normals[i] = t.degenerate[i] ? glm::dvec3(0.0) : cross / len;
        for (size_t k = 0; k < 3; ++k) t.corners[i][k] = welded[m.indices[3 * i + k]];
        if (t.degenerate[i]) continue;
        for (size_t e = 0; e < 3; ++e)
            t.edges[MeshTopology::key(t.corners[i][e], t.corners[i][(e + 1) % 3])].push_back(
                uint32_t(i));
    }
    return t;
}

// An orthonormal basis of the plane with unit normal n: the world axis least aligned with n,
// made perpendicular to it (so a floor's charts are axis-aligned), and n x that.
void planeBasis(const glm::dvec3& n, glm::dvec3& tangent, glm::dvec3& bitangent) {
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::fabs(n[k]) < std::fabs(n[axis])) axis = k;
    glm::dvec3 e(0.0);
    e[axis] = 1.0;
    tangent = glm::normalize(e - n * n[axis]);
    bitangent = glm::cross(n, tangent);
}

// A chart's side in texels for an extent in world units: at least one texel; a hair over a whole
// number of texels (float coordinates of an exact size) does not take one more.
int chartSide(double extent, const AtlasSettings& s) {
    const double texels = extent * s.texelsPerUnit;
    if (!(texels <= double(kMaxAtlasSide - 2 * s.padding)))
        throwInputError("technique " + s.technique, "texels_per_unit",
                        "a chart of " + number(extent) + " units at " + number(s.texelsPerUnit) +
                            " texels per unit is wider than " + "the atlas's limit of " +
                            std::to_string(kMaxAtlasSide) +
                            " texels (docs/techniques.md, Lightmaps)");
    return std::max(1, int(std::ceil(texels - 1e-6)));
}

// Chart-local texel coordinates of each triangle, and the charts (without their place yet).
struct MeshLayout {
    std::vector<AtlasChart> charts;
    std::vector<std::array<glm::dvec2, 3>> local;
    std::vector<int32_t> chartOf;  // index into `charts`, or -1
};

// Fills the chart's size and its triangles' local coordinates from their projections.
void placeInChart(const std::vector<Tri2>& projected, const AtlasSettings& s, AtlasChart& chart,
                  MeshLayout& layout) {
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const Tri2& t : projected)
        for (const glm::dvec2& p : t.p) lo = glm::min(lo, p), hi = glm::max(hi, p);
    chart.width = chartSide(hi.x - lo.x, s);
    chart.height = chartSide(hi.y - lo.y, s);
    for (size_t i = 0; i < chart.triangles.size(); ++i)
        for (size_t k = 0; k < 3; ++k)
            layout.local[chart.triangles[i]][k] = (projected[i].p[k] - lo) * s.texelsPerUnit;
}

// Charts of coplanar connected triangles: each grows from the lowest triangle not yet in one,
// breadth first, across edges shared by a triangle of the same plane and orientation whose
// projection overlaps none of the chart's.
MeshLayout generatedCharts(const MeshPrimitive& m, size_t mesh, const AtlasSettings& s) {
    const MeshTopology topo = topologyOf(m);
    const size_t n = m.triangleCount();
    MeshLayout layout;
    layout.local.resize(n);
    layout.chartOf.assign(n, -1);
    for (size_t seed = 0; seed < n; ++seed) {
        if (topo.degenerate[seed] || layout.chartOf[seed] >= 0) continue;
        const glm::dvec3 normal = topo.normals[seed];
        glm::dvec3 T, B;
        planeBasis(normal, T, B);
        auto project = [&](size_t t) {
            Tri2 p;
            for (size_t k = 0; k < 3; ++k) {
                const glm::dvec3& w = m.wsPositions[m.indices[3 * t + k]];
                p.p[k] = glm::dvec2(glm::dot(T, w), glm::dot(B, w));
            }
            return p;
        };
        const Tri2 first = project(seed);
        double longest = 0.0;
        for (size_t k = 0; k < 3; ++k)
            longest = std::max(longest, glm::length(first.p[(k + 1) % 3] - first.p[k]));
        OverlapGrid grid(2.0 * longest);
        AtlasChart chart;
        chart.mesh = mesh;
        std::vector<Tri2> projected;
        const int32_t id = int32_t(layout.charts.size());
        auto take = [&](size_t t, const Tri2& p) {
            layout.chartOf[t] = id;
            chart.triangles.push_back(uint32_t(t));
            projected.push_back(p);
            grid.add(p);
        };
        take(seed, first);
        std::deque<size_t> queue{seed};
        while (!queue.empty()) {
            const size_t t = queue.front();
            queue.pop_front();
            for (size_t e = 0; e < 3; ++e) {
                const uint32_t a = topo.corners[t][e], b = topo.corners[t][(e + 1) % 3];
                for (uint32_t nb : topo.edges.at(MeshTopology::key(a, b))) {
                    if (layout.chartOf[nb] >= 0 ||
                        glm::dot(topo.normals[nb], normal) < kCoplanarCos ||
                        !topo.hasDirected(nb, b, a))
                        continue;
                    const Tri2 p = project(nb);
                    if (grid.overlaps(p)) continue;
                    take(nb, p);
                    queue.push_back(nb);
                }
            }
        }
        placeInChart(projected, s, chart, layout);
        layout.charts.push_back(std::move(chart));
    }
    return layout;
}

// A mesh laid out by its own TEXCOORD_1: one chart over the coordinates' bounds, scaled so that
// its texels per unit of surface are the density's on average (sqrt of world area over uv area).
MeshLayout texcoord1Chart(const MeshPrimitive& m, size_t mesh, const AtlasSettings& s) {
    if (m.lightmapUvs.size() != m.wsPositions.size())
        throwInputError(m.name, "TEXCOORD_1",
                        std::to_string(m.lightmapUvs.size()) + " coordinates for " +
                            std::to_string(m.wsPositions.size()) + " vertices");
    const size_t n = m.triangleCount();
    MeshLayout layout;
    layout.local.resize(n);
    layout.chartOf.assign(n, -1);
    AtlasChart chart;
    chart.mesh = mesh;
    chart.fromTexcoord1 = true;
    double worldArea = 0.0, uvArea = 0.0;
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (size_t t = 0; t < n; ++t) {
        const uint32_t* i = &m.indices[3 * t];
        const double area =
            0.5 * glm::length(glm::cross(m.wsPositions[i[1]] - m.wsPositions[i[0]],
                                         m.wsPositions[i[2]] - m.wsPositions[i[0]]));
        if (!(area > 0.0)) continue;
        const glm::dvec2 a(m.lightmapUvs[i[0]]), b(m.lightmapUvs[i[1]]), c(m.lightmapUvs[i[2]]);
        worldArea += area;
        uvArea += 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
        for (const glm::dvec2& p : {a, b, c}) lo = glm::min(lo, p), hi = glm::max(hi, p);
        layout.chartOf[t] = 0;
        chart.triangles.push_back(uint32_t(t));
    }
    if (chart.triangles.empty()) return {};
    if (!(uvArea > 0.0))
        throwInputError(m.name, "TEXCOORD_1", "its triangles span no area: nothing to bake into");
    const double texelsPerUv = s.texelsPerUnit * std::sqrt(worldArea / uvArea);
    chart.width = chartSide((hi.x - lo.x) * texelsPerUv / s.texelsPerUnit, s);
    chart.height = chartSide((hi.y - lo.y) * texelsPerUv / s.texelsPerUnit, s);
    for (uint32_t t : chart.triangles)
        for (size_t k = 0; k < 3; ++k)
            layout.local[t][k] =
                (glm::dvec2(m.lightmapUvs[m.indices[3 * t + k]]) - lo) * texelsPerUv;
    layout.charts.push_back(std::move(chart));
    return layout;
}

[[noreturn]] void tooLarge(const AtlasSettings& s, const std::string& what, uint64_t texels) {
    throwInputError("technique " + s.technique, "texels_per_unit",
                    what + " at " + number(s.texelsPerUnit) + " texels per unit need " +
                        std::to_string(texels) + " texels, over the atlas's limit of " +
                        std::to_string(kMaxAtlasTexels) +
                        " (2^24, docs/techniques.md, Lightmaps): lower texels_per_unit");
}

// The static surfaces' area times the density squared: a lower bound on the atlas, checked
// before any chart is made.
void checkArea(const Scene& scene, const AtlasSettings& s) {
    double area = 0.0;
    for (const MeshPrimitive& m : scene.meshes) {
        if (m.dynamic) continue;
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const uint32_t* i = &m.indices[3 * t];
            area += 0.5 * glm::length(glm::cross(m.wsPositions[i[1]] - m.wsPositions[i[0]],
                                                 m.wsPositions[i[2]] - m.wsPositions[i[0]]));
        }
    }
    const double texels = area * s.texelsPerUnit * s.texelsPerUnit;
    if (texels > double(kMaxAtlasTexels))
        tooLarge(s, "the static surfaces' " + number(area) + " square units",
                 uint64_t(std::min(texels, 1e18)));
}

// Shelf packing, tallest first (ties: wider first, then in order), each chart in a slot of its
// size plus the padding on every side, into an atlas about as wide as the slots' area is square.
void pack(std::vector<AtlasChart>& charts, const AtlasSettings& s, int& width, int& height) {
    const int p = s.padding;
    std::vector<size_t> order(charts.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        if (charts[a].height != charts[b].height) return charts[a].height > charts[b].height;
        return charts[a].width > charts[b].width;
    });
    uint64_t slotArea = 0;
    int widest = 0;
    for (const AtlasChart& c : charts) {
        slotArea += uint64_t(c.width + 2 * p) * uint64_t(c.height + 2 * p);
        widest = std::max(widest, c.width + 2 * p);
    }
    if (slotArea > kMaxAtlasTexels) tooLarge(s, "the charts with their padding", slotArea);
    // An empty atlas (nothing static) is one texel: GL has no empty textures.
    width = std::max({1, widest, int(std::ceil(std::sqrt(double(slotArea))))});
    int x = 0, y = 0, shelf = 0;
    for (size_t i : order) {
        AtlasChart& c = charts[i];
        if (x + c.width + 2 * p > width) {
            x = 0;
            y += shelf;
            shelf = 0;
        }
        c.x = x + p;
        c.y = y + p;
        x += c.width + 2 * p;
        shelf = std::max(shelf, c.height + 2 * p);
    }
    height = std::max(1, y + shelf);
    const uint64_t texels = uint64_t(width) * uint64_t(height);
    if (height > kMaxAtlasSide || texels > kMaxAtlasTexels)
        tooLarge(
            s, "the packed atlas (" + std::to_string(width) + " x " + std::to_string(height) + ")",
            texels);
}

}  // namespace

LightmapAtlas buildLightmapAtlas(const Scene& scene, const AtlasSettings& s) {
    checkArea(scene, s);
    LightmapAtlas atlas;
    atlas.corners.resize(scene.meshes.size());
    atlas.chartOf.resize(scene.meshes.size());
    std::vector<MeshLayout> layouts(scene.meshes.size());
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const MeshPrimitive& m = scene.meshes[mi];
        atlas.corners[mi].resize(m.triangleCount());
        if (m.dynamic) {
            ++atlas.dynamicMeshes;
            atlas.dynamicTriangles += m.triangleCount();
            atlas.chartOf[mi].assign(m.triangleCount(), -1);
            continue;
        }
        const bool own = !m.lightmapUvs.empty();
        atlas.texcoord1Meshes += own;
        layouts[mi] = own ? texcoord1Chart(m, mi, s) : generatedCharts(m, mi, s);
        atlas.chartOf[mi] = layouts[mi].chartOf;
        if (atlas.chartOf[mi].empty()) atlas.chartOf[mi].assign(m.triangleCount(), -1);
        // Chart indices become the atlas's.
        for (int32_t& c : atlas.chartOf[mi])
            if (c >= 0) c += int32_t(atlas.charts.size()), ++atlas.bakedTriangles;
        for (AtlasChart& c : layouts[mi].charts) atlas.charts.push_back(std::move(c));
    }
    pack(atlas.charts, s, atlas.width, atlas.height);
    for (size_t mi = 0; mi < scene.meshes.size(); ++mi)
        for (size_t t = 0; t < atlas.chartOf[mi].size(); ++t) {
            const int32_t c = atlas.chartOf[mi][t];
            if (c < 0) continue;
            const glm::dvec2 origin(atlas.charts[size_t(c)].x, atlas.charts[size_t(c)].y);
            for (size_t k = 0; k < 3; ++k)
                atlas.corners[mi][t][k] = origin + layouts[mi].local[t][k];
        }
    return atlas;
}

}  // namespace so
