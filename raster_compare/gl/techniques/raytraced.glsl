// raytraced (raytraced.cpp): the denoisers' full-screen passes over the traced V. Every texture is
// in GL's row order; every fetch is a tap of the work counts (SO_TAP), with the texel bytes
// defined by raytraced.cpp (RAW_, ACCUM_, FILTER_, POSITION_ and NORMAL_TEXEL_BYTES). Defines:
// PASS_TEMPORAL (reprojected accumulation of V and its first two moments), PASS_VARIANCE (V and
// its variance: temporal from the moments, spatial over 7 x 7 for young histories), PASS_ATROUS
// (one a-trous level, step u_step; with KERNEL_3X3 the 3 x 3 kernel), PASS_CLASSIFY (ffx: one
// texel per 8 x 4 tile, 1 where the tile skips the filter), PASS_RESOLVE (V into the light's
// target), PASS_PENUMBRA (a disk whose radius follows the estimated penumbra; SEARCH_RADIUS and
// PENUMBRA_TAPS defined); FFX (with PASS_TEMPORAL: FidelityFX's temporal pass, writing the moments and V with its
// variance), TILE_SKIP (the passes of ffx pass skipped tiles' rays through).
uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform vec3 u_lsEye;
uniform float u_pixelScale;

vec4 positionAt(ivec2 q) {
    SO_TAP(1, POSITION_TEXEL_BYTES);
    return texelFetch(u_position, q, 0);
}
vec3 normalAt(ivec2 q) {
    SO_TAP(1, NORMAL_TEXEL_BYTES);
    return normalize(texelFetch(u_normal, q, 0).xyz);
}
// One pixel's footprint at the local point lsP: how far apart neighbouring pixels' surfaces lie
// there (the tangent-plane stops' unit).
float footprintAt(vec3 lsP) {
    return u_pixelScale * length(lsP - u_lsEye);
}
bool inside(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
}

#if defined(PASS_TEMPORAL)
uniform sampler2D u_raw;
uniform sampler2D u_prevHistory;   // RGBA: V, first moment, second moment, history length
uniform sampler2D u_prevPosition;  // the previous frame's local positions (its frame)
uniform mat4 u_prevClipFromLocal;
uniform float u_prevScale;  // previous local = local * u_prevScale + u_prevOffset
uniform vec3 u_prevOffset;
uniform float u_alpha;
uniform int u_haveHistory;
layout(location = 0) out vec4 o_accum;

// The previous frame's history at the point, bilinear over the texels that saw the same surface
// (within one pixel footprint of its tangent plane, four along it); w 0 where none did.
vec4 reprojected(vec3 lsP, vec3 n) {
    vec3 prevLs = lsP * u_prevScale + u_prevOffset;
    float footprint = footprintAt(lsP) * u_prevScale;
    vec4 clip = u_prevClipFromLocal * vec4(prevLs, 1.0);
    if (clip.w <= 0.0) return vec4(0.0);
    ivec2 size = textureSize(u_prevHistory, 0);
    vec2 px = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(px));
    vec2 f = px - vec2(base);
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1), q = base + o;
        if (!inside(q, size)) continue;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        SO_TAP(1, POSITION_TEXEL_BYTES);
        vec4 pp = texelFetch(u_prevPosition, q, 0);
        vec3 d = pp.xyz - prevLs;
        if (pp.w == 0.0 || w <= 0.0 || abs(dot(d, n)) > footprint || length(d) > 4.0 * footprint)
            continue;
        SO_TAP(1, ACCUM_TEXEL_BYTES);
        sum += w * texelFetch(u_prevHistory, q, 0);
        wsum += w;
    }
    return wsum > 1e-3 ? vec4(sum.xyz / wsum, sum.w / wsum) : vec4(0.0);
}

#ifdef FFX
uniform sampler2D u_tiles;
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
#else
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_accum = vec4(0.0);
        return;
    }
    SO_TAP(1, RAW_TEXEL_BYTES);
    float v = texelFetch(u_raw, ij, 0).r;
    vec4 hist = u_haveHistory != 0 ? reprojected(pos.xyz, normalAt(ij)) : vec4(0.0);
    if (hist.w < 0.5) {
        o_accum = vec4(v, v, v * v, 1.0);
        return;
    }
    // SVGF 4.1: an exponential moving average, the first frames of a history averaged equally.
    float len = min(round(hist.w) + 1.0, 1024.0);
    float a = max(u_alpha, 1.0 / len);
    o_accum = vec4(mix(hist.x, v, a), mix(hist.y, v, a), mix(hist.z, v * v, a), len);
}
#endif

#elif defined(PASS_VARIANCE)
uniform sampler2D u_accum;
uniform float u_sigmaNormal;
layout(location = 0) out vec2 o_filter;
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_filter = vec2(0.0);
        return;
    }
    SO_TAP(1, ACCUM_TEXEL_BYTES);
    vec4 acc = texelFetch(u_accum, ij, 0);
    if (acc.w >= 4.0) {
        o_filter = vec2(acc.x, max(acc.z - acc.y * acc.y, 0.0));
        return;
    }
    // SVGF 4.2: too young a history for temporal moments: the moments over 7 x 7 neighbours on
    // the same surface (normal stop), and the variance from them, boosted as the history is short.
    vec3 n = normalAt(ij);
    ivec2 size = textureSize(u_accum, 0);
    vec2 m = vec2(0.0);
    float wsum = 0.0;
    for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
            ivec2 q = ij + ivec2(dx, dy);
            if (!inside(q, size) || positionAt(q).w == 0.0) continue;
            float w = pow(max(dot(n, normalAt(q)), 0.0), u_sigmaNormal);
            SO_TAP(1, ACCUM_TEXEL_BYTES);
            m += w * texelFetch(u_accum, q, 0).yz;
            wsum += w;
        }
    m /= max(wsum, 1e-6);
    o_filter = vec2(acc.x, max(m.y - m.x * m.x, 0.0) * 4.0 / acc.w);
}

#elif defined(PASS_CLASSIFY)
uniform sampler2D u_raw;
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

#elif defined(PASS_ATROUS)
uniform sampler2D u_filter;  // RG: V and its variance
uniform int u_step;
#ifdef TILE_SKIP
uniform sampler2D u_tiles;
#endif
uniform float u_sigmaLuminance, u_sigmaNormal, u_sigmaDepth;
layout(location = 0) out vec2 o_filter;
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_filter = vec2(0.0);
        return;
    }
    ivec2 size = textureSize(u_filter, 0);
    vec3 n = normalAt(ij);
    SO_TAP(1, FILTER_TEXEL_BYTES);
    vec2 c = texelFetch(u_filter, ij, 0).xy;
#ifdef TILE_SKIP
    SO_TAP(1, TILE_TEXEL_BYTES);
    if (texelFetch(u_tiles, ij / ivec2(8, 4), 0).r > 0.5) {
        o_filter = c;
        return;
    }
#endif
    // The luminance stop's scale: the variance blurred over 3 x 3 (SVGF 4.2, eq. 5).
    float var = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(ij + ivec2(dx, dy), ivec2(0), size - 1);
            SO_TAP(1, FILTER_TEXEL_BYTES);
            var += texelFetch(u_filter, q, 0).y * (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
        }
    float lumScale = u_sigmaLuminance * sqrt(max(var, 0.0)) + 1e-6;
    // Depth stop: the neighbour's distance from this pixel's tangent plane, against the change
    // one pixel's footprint per pixel of distance would make (SVGF's depth gradient, in world
    // terms).
    float footprint = footprintAt(pos.xyz);
#ifdef KERNEL_3X3
    const int R = 1;
    const float h[3] = float[3](1.0 / 2.0, 1.0 / 4.0, 0.0);
#else
    const int R = 2;
    const float h[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
#endif
    vec2 sum = vec2(c.x, c.y);
    float wsum = 1.0;
    for (int dy = -R; dy <= R; ++dy)
        for (int dx = -R; dx <= R; ++dx) {
            if (dx == 0 && dy == 0) continue;
            ivec2 q = ij + ivec2(dx, dy) * u_step;
            if (!inside(q, size)) continue;
            vec4 pq = positionAt(q);
            if (pq.w == 0.0) continue;
            SO_TAP(1, FILTER_TEXEL_BYTES);
            vec2 f = texelFetch(u_filter, q, 0).xy;
            float wn = pow(max(dot(n, normalAt(q)), 0.0), u_sigmaNormal);
            float wz = abs(dot(n, pq.xyz - pos.xyz)) /
                       (u_sigmaDepth * footprint * float(u_step) * length(vec2(dx, dy)) + 1e-9);
            float wl = abs(c.x - f.x) / lumScale;
            float w = h[abs(dx)] * h[abs(dy)] / (h[0] * h[0]) * wn * exp(-wz - wl);
            sum += vec2(w * f.x, w * w * f.y);
            wsum += w;
        }
    o_filter = vec2(sum.x / wsum, sum.y / (wsum * wsum));
}

#elif defined(PASS_PENUMBRA)
uniform sampler2D u_accum;  // x: V accumulated over time
uniform sampler2D u_raw;    // y: this frame's mean blocker distance (0: no ray was blocked)
uniform float u_lsLightSize;
uniform vec3 u_lsLightCenter;
uniform float u_maxRadius;
uniform float u_radiusScale;
uniform float u_sigmaNormal;
layout(location = 0) out vec2 o_filter;
// Ray Tracing Gems, chapter 13 (Boksansky, Wimmer, Bittner 2019): the penumbra's size from the
// blocker distance by similar triangles, w = light size x d_blocker / (d_light - d_blocker), sets
// the filter's radius. The blocker distance is the mean of the blocked rays' distances over the
// pixels around (a penumbra's lit side has none of its own), the filter a disk of PENUMBRA_TAPS
// taps on a golden-angle spiral with a normal and tangent-plane stop.
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_filter = vec2(0.0);
        return;
    }
    ivec2 size = textureSize(u_accum, 0);
    vec3 n = normalAt(ij);
    float footprint = footprintAt(pos.xyz);
    float blocker = 0.0, blockers = 0.0;
    for (int dy = -SEARCH_RADIUS; dy <= SEARCH_RADIUS; dy += 2)
        for (int dx = -SEARCH_RADIUS; dx <= SEARCH_RADIUS; dx += 2) {
            ivec2 q = ij + ivec2(dx, dy);
            if (!inside(q, size)) continue;
            SO_TAP(1, RAW_TEXEL_BYTES);
            float h = texelFetch(u_raw, q, 0).y;
            if (h > 0.0) {
                blocker += h;
                blockers += 1.0;
            }
        }
    SO_TAP(1, ACCUM_TEXEL_BYTES);
    float v = texelFetch(u_accum, ij, 0).x;
    if (blockers == 0.0) {
        o_filter = vec2(v, 0.0);
        return;
    }
    blocker /= blockers;
    float dLight = length(u_lsLightCenter - pos.xyz);
    float width = u_lsLightSize * blocker / max(dLight - blocker, 1e-6);
    float radius = min(u_radiusScale * 0.5 * width / footprint, u_maxRadius);
    float sum = v, wsum = 1.0;
    for (int k = 1; k < PENUMBRA_TAPS; ++k) {
        float r = radius * sqrt(float(k) / float(PENUMBRA_TAPS));
        float a = float(k) * 2.39996323;
        ivec2 q = ij + ivec2(round(r * vec2(cos(a), sin(a))));
        if (!inside(q, size) || q == ij) continue;
        vec4 pq = positionAt(q);
        if (pq.w == 0.0) continue;
        float w = pow(max(dot(n, normalAt(q)), 0.0), u_sigmaNormal) *
                  exp(-abs(dot(n, pq.xyz - pos.xyz)) / (footprint * max(r, 1.0)));
        SO_TAP(1, ACCUM_TEXEL_BYTES);
        sum += w * texelFetch(u_accum, q, 0).x;
        wsum += w;
    }
    o_filter = vec2(sum / wsum, radius);
}

#elif defined(PASS_RESOLVE)
uniform sampler2D u_result;  // R: V
layout(location = 0) out float o_visibility;
layout(location = 1) out float o_aliasing;
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    SO_TAP(1, RESULT_TEXEL_BYTES);
    o_visibility = clamp(texelFetch(u_result, ij, 0).r, 0.0, 1.0);
    o_aliasing = 0.0;
}
#endif
