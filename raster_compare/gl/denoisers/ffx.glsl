// ffx (ffx.cpp): AMD FidelityFX Shadow Denoiser's tile classification (PASS_CLASSIFY) and
// temporal pass (PASS_TEMPORAL, with reprojection.glsl); its a-trous passes are atrous.glsl's.
uniform sampler2D u_raw;

#if defined(PASS_CLASSIFY)
layout(location = 0) out float o_skip;
// FidelityFX's tile classification, one fragment per 8 x 4 tile (its 32-bit ray mask; loops here
// where its HLSL has wave intrinsics): a tile whose rays, and those of the tiles around it, all
// agree (all lit or all shadowed) is skipped by the temporal and spatial filters.
void main() {
    ivec2 tile = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_raw, 0);
    bool anyLit = false, anyShadowed = false;
    for (int y = -4; y < 8; ++y)
        for (int x = -8; x < 16; ++x) {
            ivec2 q = tile * ivec2(8, 4) + ivec2(x, y);
            if (!inside(q, size) || positionAt(q).w == 0.0) continue;
            SO_TAP(1, RAW_TEXEL_BYTES);
            float r = texelFetch(u_raw, q, 0).r;
            anyLit = anyLit || r > 0.0;
            anyShadowed = anyShadowed || r < 1.0;
        }
    o_skip = anyLit && anyShadowed ? 0.0 : 1.0;
}

#elif defined(PASS_TEMPORAL)
uniform sampler2D u_tiles;
layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec2 o_filter;  // V and its variance, for the a-trous passes

// The rays' mean and second moment over 17 x 17 pixels, Gaussian-weighted (sigma 4): FidelityFX's
// local neighbourhood (its 1-bit masks make the second moment the mean; spp > 1 needs both).
vec2 neighbourhood(ivec2 ij) {
    ivec2 size = textureSize(u_raw, 0);
    vec2 m = vec2(0.0);
    float wsum = 0.0;
    for (int dy = -8; dy <= 8; ++dy)
        for (int dx = -8; dx <= 8; ++dx) {
            ivec2 q = ij + ivec2(dx, dy);
            if (!inside(q, size)) continue;
            float w = exp(-float(dx * dx + dy * dy) / 32.0);
            SO_TAP(1, RAW_TEXEL_BYTES);
            float r = texelFetch(u_raw, q, 0).r;
            m += w * vec2(r, r * r);
            wsum += w;
        }
    return m / wsum;
}

// FidelityFX's temporal pass: moments as a running mean and sum of squared deviations (Welford)
// with their sample count, the history clamped to the neighbourhood's mean +- one standard
// deviation, the variance boosted over the first 16 frames, and the new frame weighing from 1 down
// to 0.05 as the count reaches 32. A skipped tile starts again from its rays.
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_accum = vec4(0.0);
        o_filter = vec2(0.0);
        return;
    }
    SO_TAP(1, RAW_TEXEL_BYTES);
    float v = texelFetch(u_raw, ij, 0).r;
    SO_TAP(1, TILE_TEXEL_BYTES);
    if (texelFetch(u_tiles, ij / ivec2(8, 4), 0).r > 0.5) {
        o_accum = vec4(v, v, 0.0, 1.0);
        o_filter = vec2(v, 0.0);
        return;
    }
    vec4 hist = u_haveHistory != 0 ? reprojected(pos.xyz, normalAt(ij)) : vec4(0.0);
    float n = hist.w < 0.5 ? 1.0 : round(hist.w) + 1.0;
    float oldMean = hist.w < 0.5 ? 0.0 : hist.y, oldS = hist.w < 0.5 ? 0.0 : hist.z;
    float mean = oldMean + (v - oldMean) / n;
    float s = oldS + (v - oldMean) * (v - mean);
    float variance = n > 1.0 ? s / (n - 1.0) : 1.0;
    vec2 local = neighbourhood(ij);
    float spatialVariance = max(local.y - local.x * local.x, 0.0);
    float sigma = sqrt(spatialVariance);
    float previous = hist.w < 0.5 ? v : hist.x;
    float clamped = clamp(previous, local.x - sigma, local.x + sigma);
    if (n < 16.0) variance = max(variance, spatialVariance) * max(16.0 - n, 1.0);
    float historyWeight = sqrt(max(32.0 - n, 0.0) / 32.0);
    float result = mix(clamped, v, mix(0.05, 1.0, historyWeight));
    o_accum = vec4(result, mean, s, n);
    o_filter = vec2(result, variance);
}
#endif
