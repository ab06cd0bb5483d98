#include "oracle/exact_alpha.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace so {

namespace {

using glm::dvec2;
using glm::dvec3;

// Texel coordinates up to this magnitude are exact integers after floor, with room for the box.
constexpr double kMaxTexelCoordinate = 4503599627370496.0;  // 2^52

// The decision at one texel value (nearest), with its own rounding margin.
AlphaAnswer decide(double alpha, const AlphaMask& m) {
    return {!(alpha < double(m.cutoff)),
            std::fabs(alpha - double(m.cutoff)) <= ExactAlpha::kAlphaMargin};
}

AlphaAnswer nearest(const AlphaTexture& t, const AlphaMask& m, dvec2 x, dvec2 tol) {
    const double factor = double(m.factor);
    AlphaAnswer out = decide(
        factor * exact_alpha::texel(t, m, int64_t(std::floor(x.x)), int64_t(std::floor(x.y))), m);
    // Every texel the float path could have read: the same decision, clear of the cutoff, or
    // ambiguous.
    for (int64_t j = int64_t(std::floor(x.y - tol.y)); j <= int64_t(std::floor(x.y + tol.y)); ++j)
        for (int64_t i = int64_t(std::floor(x.x - tol.x)); i <= int64_t(std::floor(x.x + tol.x));
             ++i) {
            const AlphaAnswer a = decide(factor * exact_alpha::texel(t, m, i, j), m);
            if (a.present != out.present || a.ambiguous) out.ambiguous = true;
        }
    return out;
}

AlphaAnswer bilinear(const AlphaTexture& t, const AlphaMask& m, dvec2 x, dvec2 tol) {
    // Texel centres sit at half-integers: the four around s = x - 0.5 and their weights.
    const dvec2 s = x - 0.5, s0 = glm::floor(s), f = s - s0;
    const int64_t i0 = int64_t(s0.x), j0 = int64_t(s0.y);
    const auto at = [&](int64_t i, int64_t j) { return exact_alpha::texel(t, m, i, j); };
    const double top = (1.0 - f.x) * at(i0, j0) + f.x * at(i0 + 1, j0);
    const double bottom = (1.0 - f.x) * at(i0, j0 + 1) + f.x * at(i0 + 1, j0 + 1);
    const double alpha = double(m.factor) * ((1.0 - f.y) * top + f.y * bottom);
    // The texels any point of the box reads; alpha changes by at most their range per texel of
    // movement along either axis.
    double lo = 1.0, hi = 0.0;
    for (int64_t j = int64_t(std::floor(s.y - tol.y)); j <= int64_t(std::floor(s.y + tol.y)) + 1;
         ++j)
        for (int64_t i = int64_t(std::floor(s.x - tol.x));
             i <= int64_t(std::floor(s.x + tol.x)) + 1; ++i) {
            const double a = at(i, j);
            lo = std::min(lo, a), hi = std::max(hi, a);
        }
    const double margin =
        double(m.factor) * std::max(0.0, hi - lo) * (tol.x + tol.y) + ExactAlpha::kAlphaMargin;
    return {!(alpha < double(m.cutoff)), std::fabs(alpha - double(m.cutoff)) <= margin};
}

// How far, in texels per axis, the float path's texel coordinates may be from the exact ones at
// a crossing of triangle abc (vertex texel coordinates q) by a ray along d (exact_alpha.h).
dvec2 texelTolerance(const dvec2 q[3], const dvec3& a, const dvec3& b, const dvec3& c,
                     const dvec3& d, double lsTol) {
    const dvec3 e1 = b - a, e2 = c - a, n = glm::cross(e1, e2);
    const double n2 = glm::dot(n, n), dd = glm::length(d);
    if (!(n2 > 0.0) || !(dd > 0.0)) return dvec2(INFINITY);
    // The gradients of the barycentrics of b and c over the triangle's plane.
    const dvec3 g1 = glm::cross(e2, n) / n2, g2 = glm::cross(n, e1) / n2;
    const dvec3 gradX = (q[1].x - q[0].x) * g1 + (q[2].x - q[0].x) * g2;
    const dvec3 gradY = (q[1].y - q[0].y) * g1 + (q[2].y - q[0].y) * g2;
    const double cosine = std::fabs(glm::dot(d, n)) / (dd * std::sqrt(n2));
    const double along = lsTol / std::max(cosine, ExactAlpha::kMinCos);
    const double maxX = std::max({std::fabs(q[0].x), std::fabs(q[1].x), std::fabs(q[2].x)});
    const double maxY = std::max({std::fabs(q[0].y), std::fabs(q[1].y), std::fabs(q[2].y)});
    return {glm::length(gradX) * along + ExactAlpha::kTexelRounding * (maxX + 1.0),
            glm::length(gradY) * along + ExactAlpha::kTexelRounding * (maxY + 1.0)};
}

}  // namespace

namespace exact_alpha {

int64_t wrapIndex(int64_t i, int64_t size, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return std::clamp<int64_t>(i, 0, size - 1);
        case TextureWrap::MirroredRepeat: {
            const int64_t period = 2 * size, m = ((i % period) + period) % period;
            return m < size ? m : period - 1 - m;
        }
        case TextureWrap::Repeat:
        default:
            return ((i % size) + size) % size;
    }
}

double texel(const AlphaTexture& t, const AlphaMask& m, int64_t i, int64_t j) {
    const int64_t x = wrapIndex(i, t.width, m.wrapS), y = wrapIndex(j, t.height, m.wrapT);
    return double(t.alpha[size_t(y) * size_t(t.width) + size_t(x)]);
}

AlphaAnswer lookup(const AlphaTexture& t, const AlphaMask& m, dvec2 x, dvec2 tol) {
    const bool finite =
        std::fabs(x.x) < kMaxTexelCoordinate && std::fabs(x.y) < kMaxTexelCoordinate;
    if (!finite) return {true, true};
    // The box the lookups scan stays within kMaxTexels (a NaN tolerance is taken as that).
    const auto capped = [](double v) {
        return v <= ExactAlpha::kMaxTexels ? v : ExactAlpha::kMaxTexels;
    };
    const dvec2 within(capped(tol.x), capped(tol.y));
    AlphaAnswer out =
        m.filter == TextureFilter::Nearest ? nearest(t, m, x, within) : bilinear(t, m, x, within);
    // Beyond kMaxTexels (or NaN) the float path's texel is not known well enough.
    if (!(tol.x <= ExactAlpha::kMaxTexels && tol.y <= ExactAlpha::kMaxTexels)) out.ambiguous = true;
    return out;
}

}  // namespace exact_alpha

ExactAlpha::ExactAlpha(const Scene& scene) : meshes_(scene.meshes.size()) {
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        if (!scene.alphaTested(m)) continue;
        const MeshPrimitive& mesh = scene.meshes[m];
        MeshAlpha& out = meshes_[m];
        out.mask = &*mesh.alpha;
        if (mesh.alpha->texture >= 0)
            out.texture = &scene.alphaTextures.at(size_t(mesh.alpha->texture));
        out.uvs = &mesh.uvs;
        out.indices = &mesh.indices;
    }
}

AlphaAnswer ExactAlpha::at(TriangleId id, const dvec3& a, const dvec3& b, const dvec3& c, double b1,
                           double b2, const dvec3& d, double lsTol) const {
    const MeshAlpha& m = meshes_.at(id.mesh);
    if (!m.mask) return {};
    if (!m.texture) return decide(double(m.mask->factor), *m.mask);
    const AlphaTexture& t = *m.texture;
    const size_t first = 3 * size_t(id.prim);
    dvec2 q[3];
    for (int k = 0; k < 3; ++k) {
        const glm::vec2 uv = (*m.uvs).at((*m.indices).at(first + size_t(k)));
        q[k] = dvec2(double(uv.x) * double(t.width), double(uv.y) * double(t.height));
    }
    const dvec2 x = (1.0 - b1 - b2) * q[0] + b1 * q[1] + b2 * q[2];
    return exact_alpha::lookup(t, *m.mask, x, texelTolerance(q, a, b, c, d, lsTol));
}

}  // namespace so
