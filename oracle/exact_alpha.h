// The alpha test of the independent re-trace (`trace --verify`, docs/oracle.md, "Verification"):
// at a crossing of an alpha-tested triangle, whether the surface is there, decided in double by
// arithmetic of its own (not core/alpha_mask.h's float code, which it checks), and whether the
// oracle's float path could decide otherwise.
//
// The texture coordinate is interpolated in double from the triangle's per-vertex coordinates
// (the loader's, KHR_texture_transform applied), scaled to texels, and the texture read by the
// rule of core/alpha_mask.h: the texel holding it (nearest) or the four nearest texel centres
// weighted bilinearly, wrapped per the sampler; the crossing counts where factor * alpha >=
// cutoff.
//
// Ambiguous: the float path computes the same lookup from a nearby point in float, so the answer
// is only certain where it is the same over every point that path could have used:
//   - texel coordinates within tol of the exact ones, per axis, where tol is
//       |grad x| * lsTol / |cos| (the float ray may pass lsTol from the reference's, which moves
//         the point along the triangle by lsTol / |cos| of the ray's angle to its normal, and
//         the texel coordinate with it by the gradient of x over the triangle)
//     + kTexelRounding * (max |x_vertex| + 1) (the float path's rounding: the interpolated uv,
//         uv * size, floor; four float roundings of 2^-24 relative at most, with room to spare);
//   - nearest: some texel in that box decides differently, or the texel's factor * alpha is
//     within kAlphaMargin of the cutoff (the float product's rounding, 2^-24 relative, with room);
//   - bilinear: |factor * alpha - cutoff| <= factor * spread * (tol_x + tol_y) + kAlphaMargin,
//     spread the range of the texels the box can read (a bound on alpha's change per texel);
//   - tol above kMaxTexels, or texel coordinates too large for exact integers: ambiguous outright.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/scene.h"
#include "oracle/exact_tracer.h"

namespace so {

class ExactAlpha final : public ExactTracer::AlphaTest {
  public:
    // The scene must outlive it: the meshes' indices, coordinates and textures are read in place.
    explicit ExactAlpha(const Scene& scene);
    AlphaAnswer at(TriangleId id, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                   double b1, double b2, const glm::dvec3& d, double lsTol) const override;

    static constexpr double kTexelRounding = 1.0 / 1048576.0;  // 2^-20, of |texel coordinate| + 1
    static constexpr double kAlphaMargin = 1.0 / 1048576.0;    // 2^-20 of alpha
    static constexpr double kMaxTexels = 2.0;
    // A ray closer than this to the triangle's plane (|cos|) is taken at this angle: the point's
    // uncertainty along the plane is then lsTol * 10^6, which makes any real mask ambiguous.
    static constexpr double kMinCos = 1e-6;

  private:
    struct MeshAlpha {
        const AlphaMask* mask = nullptr;  // null: not alpha-tested
        const AlphaTexture* texture = nullptr;
        const std::vector<glm::vec2>* uvs = nullptr;
        const std::vector<uint32_t>* indices = nullptr;
    };
    std::vector<MeshAlpha> meshes_;
};

// The building blocks, exposed for tests.
namespace exact_alpha {

// Texel index i wrapped into [0, size) as OpenGL wraps it, in integers.
int64_t wrapIndex(int64_t i, int64_t size, TextureWrap wrap);
// The texel (i, j), wrapped per the mask's sampler.
double texel(const AlphaTexture& t, const AlphaMask& m, int64_t i, int64_t j);
// Whether factor * alpha >= cutoff at texel coordinates x (uv times the texture's size), and
// whether the float path could decide otherwise within the tolerance tol (texels, per axis).
AlphaAnswer lookup(const AlphaTexture& t, const AlphaMask& m, glm::dvec2 x, glm::dvec2 tol);

}  // namespace exact_alpha
}  // namespace so
