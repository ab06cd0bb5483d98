#include "core/alpha_mask.h"

#include <algorithm>
#include <cmath>

namespace so {

int wrapTexel(double i, int size, TextureWrap wrap) {
    // In double: exact for any texel index a float uv can give (|u * size| < 2^53).
    const double n = double(size);
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return int(std::clamp(i, 0.0, n - 1.0));
        case TextureWrap::MirroredRepeat: {
            const double m = i - 2.0 * n * std::floor(i / (2.0 * n));  // in [0, 2n)
            return int(m < n ? m : 2.0 * n - 1.0 - m);
        }
        case TextureWrap::Repeat:
        default:
            return int(i - n * std::floor(i / n));
    }
}

namespace {

float texel(const AlphaTexture& t, const AlphaMask& m, double x, double y) {
    const int tx = wrapTexel(x, t.width, m.wrapS), ty = wrapTexel(y, t.height, m.wrapT);
    return t.alpha[size_t(ty) * size_t(t.width) + size_t(tx)];
}

}  // namespace

float sampleAlpha(const AlphaMask& mask, const AlphaTexture* texture, glm::vec2 uv) {
    if (!texture) return mask.factor;
    // The texel coordinate in float, as a GPU computes it from a float uv.
    const float x = uv.x * float(texture->width), y = uv.y * float(texture->height);
    if (mask.filter == TextureFilter::Nearest)
        return mask.factor * texel(*texture, mask, std::floor(x), std::floor(y));
    const float sx = x - 0.5f, sy = y - 0.5f;
    const float x0 = std::floor(sx), y0 = std::floor(sy);
    const float fx = sx - x0, fy = sy - y0;
    const float a00 = texel(*texture, mask, x0, y0), a10 = texel(*texture, mask, x0 + 1.0f, y0);
    const float a01 = texel(*texture, mask, x0, y0 + 1.0f);
    const float a11 = texel(*texture, mask, x0 + 1.0f, y0 + 1.0f);
    const float top = a00 + fx * (a10 - a00), bottom = a01 + fx * (a11 - a01);
    return mask.factor * (top + fy * (bottom - top));
}

}  // namespace so
