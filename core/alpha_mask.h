// The alpha test of alpha-tested materials (docs/scene-format.md, "Alpha-tested materials"), on
// the CPU: what the oracle's Embree filter evaluates at every candidate hit. It is written to
// match OpenGL's GL_NEAREST / GL_LINEAR sampling without mipmaps, which the raster path uses
// (raster_compare/gl/shaders/alpha_test.glsl), so that where the two disagree it is the
// technique's error, not a different mask. (A GPU may weight GL_LINEAR with 8 fractional bits:
// bilinear contours can then move by a fraction of a texel; llvmpipe matches exactly.)
#pragma once

#include <glm/vec2.hpp>

#include "core/scene.h"

namespace so {

// Texel index i (any integer) wrapped into [0, size) the way OpenGL wraps it.
int wrapTexel(double i, int size, TextureWrap wrap);

// factor * the texture's alpha at uv: the texel containing uv (Nearest), or the four nearest
// texel centres weighted bilinearly (Bilinear), as GL_NEAREST / GL_LINEAR without mipmaps.
// `texture` is null for a constant-alpha mask.
float sampleAlpha(const AlphaMask& mask, const AlphaTexture* texture, glm::vec2 uv);

// Whether the surface is there at uv: alpha >= cutoff (glTF: "rendered fully opaque").
inline bool alphaKeeps(const AlphaMask& mask, const AlphaTexture* texture, glm::vec2 uv) {
    return !(sampleAlpha(mask, texture, uv) < mask.cutoff);
}

}  // namespace so
