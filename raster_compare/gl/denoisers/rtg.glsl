// rtg (rtg.cpp): Ray Tracing Gems ch. 13's passes. Line numbers are of Apress/ray-tracing-gems
// 424bf8d, Ch_13_.../dxrShadows/Data/: rt.hlsl = DXRShadows.rt.hlsl, utils = CommonUtils.hlsl,
// motion = MotionVectors.ps.hlsl, variation = VariationFilteringPass.ps.hlsl, visibility =
// VisibilityFilteringPass.ps.hlsl. PASS_COUNT and PASS_TEMPORAL are the ray generation shader's
// two halves (before and after its TraceRay calls, which are Embree's here), PASS_VARIATION and
// PASS_FILTER the two filtering passes.
uniform sampler2D u_prevHistory;   // the visibility cache: V of the last 4 frames, newest in R
uniform sampler2D u_prevPosition;  // the previous frame's local positions (its frame)
uniform sampler2D u_prevVariation;  // its variation and sample-count cache (utils 135-145)
uniform sampler2D u_prevFiltered;   // its filtered variation (R)
uniform mat4 u_prevClipFromLocal;
uniform int u_haveHistory;
uniform float u_reprojectionDepth;  // motion 50: maxReprojectionDepthDifference

// Where the point lay in the previous frame, in its pixels (px, texel centres at integers), and
// whether reverse reprojection succeeded (motion 42-51: inside the frame, and the previous frame's
// surface there at the same linear depth within u_reprojectionDepth, relative). rt.hlsl 313.
bool reproject(vec3 lsP, out vec2 px) {
    px = vec2(-10.0);
    if (u_haveHistory == 0) return false;
    vec4 clip = u_prevClipFromLocal * vec4(previousLocal(lsP), 1.0);
    if (clip.w <= 0.0) return false;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    ivec2 size = textureSize(u_prevPosition, 0);
    px = uv * vec2(size) - 0.5;
    ivec2 q = clamp(ivec2(floor(px + 0.5)), ivec2(0), size - 1);
    SO_TAP(1, POSITION_TEXEL_BYTES);
    vec4 prev = texelFetch(u_prevPosition, q, 0);
    if (prev.w == 0.0) return false;
    float prevDepth = (u_prevClipFromLocal * vec4(prev.xyz, 1.0)).w;
    return abs(1.0 - clip.w / prevDepth) <= u_reprojectionDepth;
}

// utils 140-144: the caches of variation (fraction) and sample counts (integer part, plus one).
vec4 decodeVariation(vec4 encoded, out ivec4 counts) {
    counts = ivec4(trunc(encoded)) - ivec4(1);
    return fract(encoded) / 0.99;
}

// A cache texel at this pixel (not reprojected: rt.hlsl 323, 360, 365), zero before any history
// (the chapter's cleared textures).
vec4 cacheAt(sampler2D cache, ivec2 ij) {
    if (u_haveHistory == 0) return vec4(0.0);
    SO_TAP(1, STATE_TEXEL_BYTES);
    return texelFetch(cache, ij, 0);
}

#if defined(PASS_COUNT)
uniform int u_maxCount;        // maxLightSamplesCount: the technique's spp
uniform float u_threshold;     // variationThreshold
uniform int u_samplingMatrix;  // APPLY_SAMPLING_MATRIX
uniform int u_blockSize;       // cullingBlockSize
uniform int u_frameMod4;       // frameNumber: the frame index % 4
layout(location = 0) out float o_count;

// rt.hlsl 343-349: whether the 4 x 4 matrix of blocks leaves this pixel out of this frame.
bool matrixSkips(ivec2 ij) {
    const int mask[16] = int[16](0, 3, 2, 1, 2, 1, 0, 3, 0, 3, 2, 1, 1, 2, 0, 3);
    ivec2 e = (ij / u_blockSize) % 4;
    return mask[e.x * 4 + e.y] != u_frameMod4;
}

// rt.hlsl 373-413: the pixel's ray count (0 where the sampling matrix skips it), from its own
// previous counts and variations.
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_count = 0.0;
        return;
    }
    vec2 px;
    bool rejected = !reproject(pos.xyz, px);
    ivec2 previous = rejected ? ij : clamp(ivec2(floor(px + 0.5)), ivec2(0),
                                           textureSize(u_prevFiltered, 0) - 1);
    ivec4 past;
    vec4 variationHistory = decodeVariation(cacheAt(u_prevVariation, ij), past);
    float filtered = cacheAt(u_prevFiltered, ij).r;
    float filteredReprojected = cacheAt(u_prevFiltered, previous).r;
    if (u_samplingMatrix != 0 && !rejected && filtered == 0.0 && filteredReprojected == 0.0 &&
        matrixSkips(ij)) {
        o_count = 0.0;
        return;
    }
    int count = past.r;
    float current = (filtered + dot(variationHistory, vec4(0.25))) * 0.5;
    if (current < u_threshold) {
        // Fewer rays only after three frames at the same count.
        if (past.r == past.g && past.r == past.b) count = past.r - 1;
    } else if (current > u_threshold) {
        count = past.r + 1;
    }
    if (rejected) count = u_maxCount;
    o_count = float(clamp(count, 1, u_maxCount));
}

#elif defined(PASS_TEMPORAL)
uniform sampler2D u_raw;
uniform sampler2D u_counts;
layout(location = 0) out vec4 o_visibilityCache;  // accum
layout(location = 1) out vec4 o_variationCache;
layout(location = 2) out float o_variation;       // this frame's, to be filtered
layout(location = 3) out vec2 o_visibility;       // filterA: V for the Gaussian

// The visibility cache at the previous pixel px, bilinear (rt.hlsl 364: bilinearSampler).
vec4 visibilityAt(vec2 px) {
    ivec2 size = textureSize(u_prevHistory, 0);
    ivec2 base = ivec2(floor(px));
    vec2 f = px - vec2(base);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        SO_TAP(1, ACCUM_TEXEL_BYTES);
        sum += w * texelFetch(u_prevHistory, clamp(base + o, ivec2(0), size - 1), 0);
    }
    return sum;
}

// rt.hlsl 426-457: this frame's V (the rays', or the reprojected cache's where none was traced),
// the visibility cache shifted, the 4 frames' mean (utils 55-58) and their variation (utils
// 20-28), and the caches of variation and counts shifted.
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_visibilityCache = vec4(0.0);
        o_variationCache = vec4(0.0);
        o_variation = 0.0;
        o_visibility = vec2(0.0);
        return;
    }
    vec2 px;
    bool rejected = !reproject(pos.xyz, px);
    vec4 historyReprojected = rejected ? cacheAt(u_prevHistory, ij) : visibilityAt(px);
    vec4 history = cacheAt(u_prevHistory, ij);
    SO_TAP(1, COUNT_TEXEL_BYTES);
    int count = int(texelFetch(u_counts, ij, 0).r);
    SO_TAP(1, RAW_TEXEL_BYTES);
    float v = count == 0 ? historyReprojected.r : texelFetch(u_raw, ij, 0).r;
    vec4 newHistory = rejected ? vec4(v) : vec4(v, historyReprojected.rgb);
    o_visibilityCache = newHistory;
    o_visibility = vec2(dot(newHistory, vec4(0.25)), 0.0);
    vec4 last4 = vec4(history.rgb, v);
    float variation = abs(max(max(last4.x, last4.y), max(last4.z, last4.w)) -
                          min(min(last4.x, last4.y), min(last4.z, last4.w)));
    ivec4 past;
    vec4 variationHistory = decodeVariation(cacheAt(u_prevVariation, ij), past);
    // rt.hlsl 450-453 as written: G, B and A all take the old R before R takes the new value.
    variationHistory = vec4(variation, variationHistory.rrr);
    // utils 135-138: counts in the integer part (plus one, so that 0 rays is kept).
    o_variationCache = variationHistory * 0.99 + vec4(ivec4(count, past.rgb)) + vec4(1.0);
    o_variation = variation;
}

#elif defined(PASS_VARIATION)
uniform sampler2D u_input;
uniform ivec2 u_step;  // (1, 0) horizontal, (0, 1) vertical
uniform int u_maximum;  // 1: distributeMaxPass (variation 53-74), 0: blurPass (variation 29-51)
layout(location = 0) out float o_variation;

// A tap out of the image is 0, as D3D's Load reads it.
float variationAt(ivec2 q) {
    if (!inside(q, textureSize(u_input, 0))) return 0.0;
    SO_TAP(1, VARIATION_TEXEL_BYTES);
    return texelFetch(u_input, q, 0).r;
}

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    float result = 0.0;
    if (u_maximum != 0) {
        for (int i = -2; i <= 2; ++i) result = max(result, variationAt(ij + i * u_step));
    } else {
        for (int i = -4; i <= 4; ++i) result += variationAt(ij + i * u_step) / 9.0;
    }
    o_variation = result;
}

#elif defined(PASS_FILTER)
uniform sampler2D u_input;      // V (R)
uniform sampler2D u_variation;  // the filtered variation
uniform ivec2 u_step;
uniform mat4 u_clipFromLocal;
uniform float u_maxVariation;  // maxVariationLevel
uniform float u_depthEpsilonMin, u_depthEpsilonMax, u_normalEpsilon;
layout(location = 0) out vec2 o_visibility;

// visibility 37-53: Gaussians of 1, 3, 5, 7 and 9 taps.
const float kGauss[45] = float[45](
    0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.0, 0.196842, 0.606316, 0.196842, 0.0, 0.0, 0.0,
    0.0, 0.0, 0.05448868, 0.2442013, 0.40262, 0.2442013, 0.05448868, 0.0, 0.0,
    0.0, 0.02397741, 0.09784279, 0.2274913, 0.301377, 0.2274913, 0.09784279, 0.02397741, 0.0,
    0.01351957, 0.04766219, 0.1172301, 0.2011676, 0.2408413, 0.2011676, 0.11723, 0.04766217,
    0.01351957);

float linearDepth(vec3 lsP) {
    return (u_clipFromLocal * vec4(lsP, 1.0)).w;
}

// visibility 55-71 (isValidTap): a binary test, the depth ratio's tolerance by the normal's
// view-space z.
bool validTap(float tapDepth, float centerDepth, vec3 tapNormal, vec3 centerNormal) {
    vec3 viewAxis = normalize(vec3(u_clipFromLocal[0][3], u_clipFromLocal[1][3],
                                   u_clipFromLocal[2][3]));
    float epsilon = mix(u_depthEpsilonMax, u_depthEpsilonMin, abs(dot(centerNormal, viewAxis)));
    if (abs(1.0 - tapDepth / centerDepth) > epsilon) return false;
    return dot(tapNormal, centerNormal) >= u_normalEpsilon;
}

// visibility 73-128 (blurPass, selectBlurPassSize): the kernel picked, and blended with the next
// larger, by the filtered variation; taps that fail the test leave the normalisation.
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    if (pos.w == 0.0) {
        o_visibility = vec2(0.0);
        return;
    }
    ivec2 size = textureSize(u_input, 0);
    SO_TAP(1, VARIATION_TEXEL_BYTES);
    float variation = clamp(texelFetch(u_variation, ij, 0).r / u_maxVariation, 0.0, 1.0);
    float kernel = variation * (4.0 - 0.01);
    int offset = int(floor(kernel)) * 9;
    float blend = fract(kernel);
    float centerDepth = linearDepth(pos.xyz);
    vec3 centerNormal = normalAt(ij);
    float acc = 0.0, weight = 1.0;
    for (int i = -4; i <= 4; ++i) {
        float w = mix(kGauss[offset + i + 4], kGauss[offset + i + 13], blend);
        ivec2 q = ij + i * u_step;
        bool valid = false;
        if (w > 0.0 && inside(q, size)) {
            vec4 tap = positionAt(q);
            valid = tap.w != 0.0 &&
                    validTap(linearDepth(tap.xyz), centerDepth, normalAt(q), centerNormal);
        }
        if (valid) {
            SO_TAP(1, FILTER_TEXEL_BYTES);
            acc += w * texelFetch(u_input, q, 0).r;
        } else {
            weight -= w;
        }
    }
    o_visibility = vec2(acc / weight, 0.0);
}
#endif
