// Visibility of one light per pixel, V in [0, 1], with the technique chosen by #defines:
//   LIGHT_ORTHO (directional), LIGHT_SPOT, LIGHT_CUBE (point and area lights, at the centre);
//   BIAS_CONSTANT, BIAS_SLOPE_ALPHA/MIN/MAX, NORMAL_OFFSET_K, PCF_RADIUS (techniques/*.cpp).
// Depths are compared as linear distances along the map's view axis, so biases are lengths:
// in texels, the world size of one shadow-map texel at the receiver.
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform vec3 u_lsEye;
uniform vec3 u_lsLightPosition;
uniform vec3 u_lsLightDirection;  // the way light travels
uniform float u_cosOuter;
uniform mat4 u_lightClipFromLocal;
uniform mat4 u_lightViewFromLocal;
uniform float u_near;
uniform float u_far;
uniform float u_texelScale;  // ortho: texel size; perspective: texel size per unit of depth
#if defined(HW_PCF) && defined(LIGHT_CUBE)
uniform samplerCubeShadow u_map;
#elif defined(HW_PCF)
uniform sampler2DShadow u_map;
#elif defined(LIGHT_CUBE)
uniform samplerCube u_map;
#else
uniform sampler2D u_map;
#endif
uniform float u_pixelScale;  // camera pixel size per unit of distance (2 tan(vfov / 2) / height)
layout(location = 0) out float o_visibility;
// Predicted aliasing (Lloyd et al.): the shadow-map texel's footprint on the receiver over the
// camera pixel's footprint there; > 1 means a texel covers more than a pixel.
layout(location = 1) out float o_aliasing;

#ifndef PCF_RADIUS
#define PCF_RADIUS 0
#endif
#ifndef BLEED_REDUCTION
#define BLEED_REDUCTION 0.0
#endif

float linearDepth(float z) {
#ifdef LIGHT_ORTHO
    return u_near + z * (u_far - u_near);
#else
    return u_near * u_far / (u_far - z * (u_far - u_near));
#endif
}

float texelWorld(float depth) {
#ifdef LIGHT_ORTHO
    return u_texelScale;
#else
    return depth * u_texelScale;
#endif
}

// The window depth the hardware compares against, for a linear depth d.
float windowDepth(float d) {
#ifdef LIGHT_ORTHO
    return (d - u_near) / (u_far - u_near);
#else
    return u_far * (d - u_near) / (d * (u_far - u_near));
#endif
}

#ifdef POISSON
// 16 points of a Poisson disk in the unit disk.
const vec2 kPoisson[16] = vec2[](vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
                                 vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
                                 vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
                                 vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
                                 vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
                                 vec2(0.14383161, -0.14100790));
#endif

#if defined(VSM) || defined(ESM) || defined(EVSM)
// Filtered techniques: the moment map, bilinearly filtered (and blurred), at the lookup.
float chebyshev(vec2 m, float t, float minVariance) {
    if (t <= m.x) return 1.0;
    float variance = max(m.y - m.x * m.x, minVariance);
    float d = t - m.x;
    return variance / (variance + d * d);
}
// Light-bleeding reduction: p below `amount` counts as shadow, the rest rescaled to [0, 1].
float reduceBleeding(float p) { return clamp((p - BLEED_REDUCTION) / (1.0 - BLEED_REDUCTION), 0.0, 1.0); }
float filtered(vec4 m, float t) {
#if defined(VSM)
    return reduceBleeding(chebyshev(m.xy, t, MIN_VARIANCE));
#elif defined(ESM)
    return clamp(exp(-ESM_C * t) * m.x, 0.0, 1.0);
#else
    float p = exp(EVSM_CPOS * t), n = -exp(-EVSM_CNEG * t);
    float vp = chebyshev(m.xy, p, MIN_VARIANCE * EVSM_CPOS * EVSM_CPOS * p * p);
    float vn = chebyshev(m.zw, n, MIN_VARIANCE * EVSM_CNEG * EVSM_CNEG * n * n);
    return reduceBleeding(min(vp, vn));
#endif
}
#endif

#ifdef LIGHT_CUBE
float lookup(vec3 q, float bias) {
    vec3 v = q - u_lsLightPosition;
    vec3 a = abs(v);
    float d = max(a.x, max(a.y, a.z));
    if (d > u_far) return 1.0;
#if defined(VSM) || defined(ESM) || defined(EVSM)
    return filtered(texture(u_map, v), clamp((d - bias - u_near) / (u_far - u_near), 0.0, 1.0));
#elif defined(HW_PCF)
    return texture(u_map, vec4(v, windowDepth(d - bias)));
#else
    // Tangent axes of the face the direction falls on, one texel apart at depth d.
    vec3 t1 = a.x >= a.y && a.x >= a.z ? vec3(0, 1, 0) : vec3(1, 0, 0);
    vec3 t2 = a.z >= a.x && a.z >= a.y ? vec3(0, 1, 0) : vec3(0, 0, 1);
    float step = u_texelScale * d;
    float lit = 0.0;
#ifdef POISSON
    for (int k = 0; k < 16; ++k) {
        vec2 o = kPoisson[k] * (float(PCF_RADIUS) + 0.5);
        lit += d - bias <= linearDepth(texture(u_map, v + step * (o.x * t1 + o.y * t2)).r) ? 1.0 : 0.0;
    }
    return lit / 16.0;
#else
    for (int dy = -PCF_RADIUS; dy <= PCF_RADIUS; ++dy)
        for (int dx = -PCF_RADIUS; dx <= PCF_RADIUS; ++dx) {
            float z = texture(u_map, v + step * (float(dx) * t1 + float(dy) * t2)).r;
            lit += d - bias <= linearDepth(z) ? 1.0 : 0.0;
        }
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
#endif
#endif
}
float receiverDepth(vec3 q) {
    vec3 a = abs(q - u_lsLightPosition);
    return max(a.x, max(a.y, a.z));
}
#else
float lookup(vec3 q, float bias) {
    vec4 c = u_lightClipFromLocal * vec4(q, 1.0);
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    float d = -(u_lightViewFromLocal * vec4(q, 1.0)).z;
    // Outside the map's frustum nothing was rendered that could shadow it.
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || d > u_far) return 1.0;
#if defined(VSM) || defined(ESM) || defined(EVSM)
    return filtered(texture(u_map, uv), clamp((d - bias - u_near) / (u_far - u_near), 0.0, 1.0));
#elif defined(HW_PCF)
    return texture(u_map, vec3(uv, windowDepth(d - bias)));
#else
    ivec2 size = textureSize(u_map, 0);
    float lit = 0.0;
#ifdef POISSON
    for (int k = 0; k < 16; ++k) {
        vec2 o = kPoisson[k] * (float(PCF_RADIUS) + 0.5);
        ivec2 ij = clamp(ivec2(floor(uv * vec2(size) + o)), ivec2(0), size - 1);
        lit += d - bias <= linearDepth(texelFetch(u_map, ij, 0).r) ? 1.0 : 0.0;
    }
    return lit / 16.0;
#else
    ivec2 base = ivec2(floor(uv * vec2(size)));
    for (int dy = -PCF_RADIUS; dy <= PCF_RADIUS; ++dy)
        for (int dx = -PCF_RADIUS; dx <= PCF_RADIUS; ++dx) {
            ivec2 ij = clamp(base + ivec2(dx, dy), ivec2(0), size - 1);
            lit += d - bias <= linearDepth(texelFetch(u_map, ij, 0).r) ? 1.0 : 0.0;
        }
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
#endif
#endif
}
float receiverDepth(vec3 q) { return -(u_lightViewFromLocal * vec4(q, 1.0)).z; }
#endif

void main() {
    vec3 p = v_lsPosition;
    vec3 n = normalize(v_lsFaceNormal);
    if (dot(n, p - u_lsEye) > 0.0) n = -n;
#ifdef LIGHT_ORTHO
    vec3 l = -u_lsLightDirection;
#else
    vec3 l = normalize(u_lsLightPosition - p);
#endif
    float ndotl = dot(n, l);
    vec3 toEye = u_lsEye - p;
    float pixel = length(toEye) * u_pixelScale / max(abs(dot(n, normalize(toEye))), 1e-3);
    o_aliasing = 0.0;
    // The oracle's conventions: facing away, or outside a spot's cone, is unlit.
    if (ndotl <= 0.0) {
        o_visibility = 0.0;
        return;
    }
#ifdef LIGHT_SPOT
    if (dot(-l, u_lsLightDirection) < u_cosOuter) {
        o_visibility = 0.0;
        return;
    }
#endif
    float texel = texelWorld(receiverDepth(p));
    o_aliasing = (texel / max(ndotl, 1e-3)) / pixel;
    vec3 q = p;
#ifdef NORMAL_OFFSET_K
    q += n * (NORMAL_OFFSET_K * texel * (1.0 - ndotl));
#endif
    float bias = 0.0;
#ifdef BIAS_CONSTANT
    bias += BIAS_CONSTANT * texel;
#endif
#ifdef BIAS_SLOPE_ALPHA
    float tanTheta = sqrt(max(0.0, 1.0 - ndotl * ndotl)) / ndotl;
    // A filter's outer taps see the receiver's plane PCF_RADIUS texels away, that much deeper.
    bias += clamp(BIAS_SLOPE_ALPHA * tanTheta, BIAS_SLOPE_MIN, BIAS_SLOPE_MAX) * texel * (1.0 + float(PCF_RADIUS));
#endif
    o_visibility = lookup(q, bias);
}
