// ffx (ffx.cpp): AMD's FidelityFX Shadow Denoiser, its three kernels as fragment passes. Citations
// are to GPUOpen-Effects/FidelityFX-Denoiser d7dfecb, ffx-shadows-dnsr/ (TC:
// ffx_denoiser_shadows_tileclassification.h, F: ffx_denoiser_shadows_filter.h), and to the
// FidelityFX SDK 1.1.4 (c6efa6b), sdk/include/FidelityFX/gpu/denoiser/ffx_denoiser_shadows_filter.h
// (SDK-F). PASS_CLASSIFY: which 8 x 8 groups skip the denoiser (TC 309-339); PASS_TEMPORAL (with
// reprojection.glsl): the temporal pass (TC 341-422); PASS_FILTER: one of the three edge-avoiding
// passes (F 170-271, SDK-F 285-329).
uniform sampler2D u_raw;  // R: this frame's V (one ray's 0 or 1 at spp 1: FFX's mask bit)

// The tiles' texel: what TC's metadata says of an 8 x 8 group (TC 289-307).
const float kActive = 0.0, kClearedShadow = 1.0, kClearedLight = 2.0;

bool receiverAt(ivec2 q) {
    return positionAt(q).w != 0.0;
}

#if defined(PASS_CLASSIFY)
layout(location = 0) out float o_tile;
// TC 309-339, one fragment per 8 x 8 group: a group without a receiver is cleared in shadow (TC
// 316-322); one whose region, 8 x 4 ray masks i in [-1, 1] by j in [-2, 3] around it (TC 66-80:
// 8 pixels on every side, the 1 + 2 + 4 the filters reach), is all lit or all shadowed is cleared
// so (TC 82-83, 326-337). A pixel without a surface reads as FFX's mask bit where no ray was traced
// (0); the region is clamped to the image (TC 73).
void main() {
    ivec2 group = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_raw, 0);
    bool anyReceiver = false;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            ivec2 q = group * 8 + ivec2(x, y);
            anyReceiver = anyReceiver || (inside(q, size) && receiverAt(q));
        }
    if (!anyReceiver) {
        o_tile = kClearedShadow;
        return;
    }
    bool allLit = true, allShadowed = true;
    for (int y = -8; y < 16; ++y)
        for (int x = -8; x < 16; ++x) {
            ivec2 q = group * 8 + ivec2(x, y);
            if (!inside(q, size)) continue;
            SO_TAP(1, RAW_TEXEL_BYTES);
            float r = texelFetch(u_raw, q, 0).r;
            allLit = allLit && r == 1.0;
            allShadowed = allShadowed && r == 0.0;
        }
    o_tile = allLit ? kClearedLight : allShadowed ? kClearedShadow : kActive;
}

#elif defined(PASS_TEMPORAL)
uniform sampler2D u_tiles;
uniform mat4 u_clipFromLocal;  // this frame's: the view depth is its w
layout(location = 0) out vec4 o_accum;   // V, the moments' mean, their sum of squares, the count
layout(location = 1) out vec2 o_filter;  // V and its variance, the filters' input

// TC 166-182: the 17-tap kernel, exp(-3 i^2 / (8 + 1)^2), normalised in one dimension.
float[17] kernelWeights() {
    float w[17];
    float sum = 0.0;
    for (int i = 0; i < 17; ++i) {
        w[i] = exp(-3.0 * float((i - 8) * (i - 8)) / 81.0);
        sum += w[i];
    }
    for (int i = 0; i < 17; ++i) w[i] /= sum;
    return w;
}

// TC 190-287: the rays' mean over 17 x 17 pixels, a separable Gaussian whose taps outside the
// image count as 0 (TC 196, 208-212) and keep their weight; y: the second moment (FFX's one bit a
// pixel makes it the mean, TC 186; spp > 1 needs both).
vec2 localNeighbourhood(ivec2 ij) {
    float w[17] = kernelWeights();
    ivec2 size = textureSize(u_raw, 0);
    vec2 m = vec2(0.0);
    for (int dy = -8; dy <= 8; ++dy)
        for (int dx = -8; dx <= 8; ++dx) {
            ivec2 q = ij + ivec2(dx, dy);
            if (!inside(q, size)) continue;
            SO_TAP(1, RAW_TEXEL_BYTES);
            float r = texelFetch(u_raw, q, 0).r;
            m += w[dx + 8] * w[dy + 8] * vec2(r, r * r);
        }
    return m;
}

// TC 95-132 (FFX_DNSR_Shadows_IsDisoccluded): the point's view depth in the previous frame
// against the previous depth at the texel it lands in, apart by at least 1% to 10% as the surface
// turns from the eye (TC 116-128). `prevTexel` gets that texel (TC 122, 348).
bool disoccluded(vec3 lsP, vec3 n, out ivec2 prevTexel) {
    vec3 prevLs = previousLocal(lsP);
    vec4 clip = u_prevClipFromLocal * vec4(prevLs, 1.0);
    prevTexel = ivec2(0);
    if (clip.w <= 0.0) return true;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThanEqual(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return true;
    ivec2 size = textureSize(u_prevHistory, 0);
    prevTexel = ivec2(uv * vec2(size));
    SO_TAP(1, POSITION_TEXEL_BYTES);
    vec4 pp = texelFetch(u_prevPosition, prevTexel, 0);
    if (pp.w == 0.0) return true;  // FFX's far plane: no depth matches it
    float previousDepth = (u_prevClipFromLocal * vec4(pp.xyz, 1.0)).w;
    float zAlignment = pow(1.0 - dot(normalize(u_lsEye - lsP), n), 8.0);
    return abs(previousDepth - clip.w) / clip.w >= mix(1e-2, 1e-1, zAlignment);
}

// TC 395 (FFX_DNSR_Shadows_ReadHistory: a bilinear, clamp-to-edge sample) of the previous
// frame's first filter pass, where its uv lands (no surface test: the clamp bounds it).
float previousShadow(vec3 lsP, float current) {
    vec4 clip = u_prevClipFromLocal * vec4(previousLocal(lsP), 1.0);
    if (clip.w <= 0.0) return current;
    ivec2 size = textureSize(u_prevHistory, 0);
    vec2 px = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(px));
    vec2 f = px - vec2(base);
    float sum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 q = clamp(base + o, ivec2(0), size - 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        SO_TAP(1, ACCUM_TEXEL_BYTES);
        sum += w * texelFetch(u_prevHistory, q, 0).x;
    }
    return sum;
}

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    bool receiver = pos.w != 0.0;
    SO_TAP(1, TILE_TEXEL_BYTES);
    float tile = texelFetch(u_tiles, ij / 8, 0).r;
    if (tile != kActive) {  // TC 300-307: cleared to the region's value, a count of 1
        float shadow = tile == kClearedLight ? 1.0 : 0.0;
        o_accum = vec4(shadow, shadow, 0.0, receiver ? 1.0 : 0.0);
        o_filter = vec2(shadow, 0.0);
        return;
    }
    if (!receiver) {  // TC 355-358
        o_accum = vec4(0.0);
        o_filter = vec2(0.0);
        return;
    }
    SO_TAP(1, RAW_TEXEL_BYTES);
    float current = texelFetch(u_raw, ij, 0).r;
    vec3 n = normalAt(ij);
    // TC 365-376: Welford's running mean and sum of squares with their count, restarted where the
    // point was disoccluded.
    ivec2 prevTexel;
    vec3 previous = vec3(0.0);  // mean, sum of squares, count
    if (u_haveHistory != 0 && !disoccluded(pos.xyz, n, prevTexel)) {
        SO_TAP(1, ACCUM_TEXEL_BYTES);
        previous = texelFetch(u_prevHistory, prevTexel, 0).yzw;
    }
    float count = previous.z + 1.0;
    float mean = previous.x + (current - previous.x) / count;
    float s = previous.y + (current - previous.x) * (current - mean);
    float variance = count > 1.0 ? s / (count - 1.0) : 1.0;
    // TC 381-412: the history clamped to the neighbourhood's mean +- half a standard deviation,
    // the count damped by how far the history lies from that mean, the variance boosted while
    // the count is under 16.
    vec2 local = localNeighbourhood(ij);
    float spatialVariance = max(local.y - local.x * local.x, 0.0);
    float deviation = sqrt(spatialVariance);
    float shadowPrevious = u_haveHistory != 0 ? previousShadow(pos.xyz, current) : current;
    float clamped = clamp(shadowPrevious, local.x - 0.5 * deviation, local.x + 0.5 * deviation);
    float discontinuity = (shadowPrevious - local.x) / max(0.5 * deviation, 0.001);
    count *= exp(-discontinuity * discontinuity / 20.0);
    if (count < 16.0) variance = max(variance, spatialVariance) * max(16.0 - count, 1.0);
    // TC 416-417: the new frame weighs 1 down to 0.05 as the count reaches 8.
    float historyWeight = sqrt(max(8.0 - count, 0.0) / 8.0);
    float shadow = mix(clamped, current, mix(0.05, 1.0, historyWeight));
    o_accum = vec4(shadow, mean, s, count);
    o_filter = vec2(shadow, variance);
}

#elif defined(PASS_FILTER)
uniform sampler2D u_filter;  // RG: V and its variance
uniform sampler2D u_tiles;
uniform mat4 u_clipFromLocal;
uniform int u_step;                // F's stepsize: 1, 2, 4 (SDK-F 288, 302, 316)
uniform int u_last;                // the third pass, which remaps the contrast (SDK-F 321-323)
uniform float u_lsDepthSimilarity;  // depth_similarity_sigma in local units
layout(location = 0) out vec2 o_filter;

// F 72-80: every read clamped to the image.
vec2 inputAt(ivec2 q) {
    SO_TAP(1, FILTER_TEXEL_BYTES);
    return texelFetch(u_filter, clamp(q, ivec2(0), textureSize(u_filter, 0) - 1), 0).xy;
}

// F 170-237: the 3 x 3 kernel {1, 2/3} (F 185 declares {1, 2/3, 1/6}; k = 1 reads the first
// two) at the step, stopped by V against the 3 x 3-blurred standard deviation (F 126-129, 150-168,
// 180), the view depth (F 131-134) and the normals' cosine to the power 32 (F 136-139); taps
// without a surface weigh nothing (F 200).
vec2 filtered(ivec2 ij, vec4 pos) {
    ivec2 size = textureSize(u_filter, 0);
    vec2 center = inputAt(ij);
    float variance = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
            variance += (x == 0 ? 0.5 : 0.25) * (y == 0 ? 0.5 : 0.25) * inputAt(ij + ivec2(x, y)).y;
    float deviation = sqrt(max(variance + 1e-9, 0.0));
    float depth = (u_clipFromLocal * vec4(pos.xyz, 1.0)).w;
    vec3 n = normalAt(ij);
    const float kernel[2] = float[2](1.0, 2.0 / 3.0);
    vec2 sum = center;
    float weightSum = 1.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            if (x == 0 && y == 0) continue;
            ivec2 q = clamp(ij + ivec2(x, y) * u_step, ivec2(0), size - 1);
            vec4 pq = positionAt(q);
            if (pq.w == 0.0) continue;
            vec2 neighbour = inputAt(q);
            float w = kernel[abs(x)] * kernel[abs(y)];
            w *= exp(-abs(center.x - neighbour.x) / deviation);
            w *= exp(-abs(depth - (u_clipFromLocal * vec4(pq.xyz, 1.0)).w) / u_lsDepthSimilarity);
            w *= pow(clamp(dot(n, normalAt(q)), 0.0, 1.0), 32.0);
            sum += vec2(w, w * w) * neighbour;
            weightSum += w;
        }
    return vec2(sum.x / weightSum, sum.y / (weightSum * weightSum));
}

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    SO_TAP(1, TILE_TEXEL_BYTES);
    float tile = texelFetch(u_tiles, ij / 8, 0).r;
    vec2 result;
    if (tile != kActive)  // F 256-262 (the second pass leaves TC's identical value)
        result = vec2(tile == kClearedLight ? 1.0 : 0.0, 0.0);
    else {
        vec4 pos = positionAt(ij);
        result = pos.w == 0.0 ? vec2(0.0) : filtered(ij, pos);  // F 225-236
    }
    // SDK-F 321-323: "recover some of the contrast lost during denoising".
    if (u_last != 0) result.x = pow(abs(result.x), max(1.2 - result.y, 1.0));
    o_filter = result;
}
#endif
