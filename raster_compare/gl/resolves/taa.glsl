// resolve=taa (resolves/taa.cpp): the lit image resolved by Bevy's TAA, as Bevy 0.19.1 ships it
// (bevyengine/bevy b56fc29d, crates/bevy_anti_alias/src/taa/taa.wgsl, the same lines in every tag
// from 0.14.0; line numbers below are that file's). The lit image is two grey images of white
// Lambert surfaces lit by the one light, shadowed (V E) and unshadowed (E), each resolved as a
// view target is; V is recovered from them, as the engine pages recover it. The view is LDR
// (TONEMAP undefined, taa/mod.rs: only HDR views tonemap), so colours stay in [0, 1].
uniform sampler2D u_prevHistoryLinear;  // the same history, bilinear (taa.wgsl:18, 66)
uniform mat4 u_unjitteredClipFromLocal;  // this frame's camera without the jitter (motion vectors)
uniform vec3 u_lsLight;                  // directional: the way to the light; else its centre
uniform int u_lightDirectional;
uniform vec3 u_lsEye;  // this frame's camera

const float DEFAULT_HISTORY_BLEND_RATE = 0.1;  // taa.wgsl:10
const float MIN_HISTORY_BLEND_RATE = 0.015;    // taa.wgsl:11

// This frame's lit image at q: (shadowed, unshadowed) of a white Lambert surface, E = max(0, n.l)
// (the light's falloff left out, so that the image stays within the LDR view's [0, 1]).
vec2 litAt(ivec2 q) {
    q = clamp(q, ivec2(0), textureSize(u_position, 0) - 1);  // the sampler's clamp to edge
    vec4 p = positionAt(q);
    if (p.w == 0.0) return vec2(0.0);
    vec3 l = u_lightDirectional != 0 ? u_lsLight : normalize(u_lsLight - p.xyz);
    float e = max(dot(normalize(normalAt(q).xyz), l), 0.0);
    return vec2(visibilityAt(q) * e, e);
}

// The motion vector of pixel q (uv now - uv before, unjittered, as Bevy's prepass writes it:
// prepass.wgsl:195-205) and its closeness (1 / distance; 0: nothing there, a cleared 0 vector).
vec3 motionAt(ivec2 q) {
    q = clamp(q, ivec2(0), textureSize(u_position, 0) - 1);
    vec4 p = positionAt(q);
    if (p.w == 0.0) return vec3(0.0);
    Reprojected r = reproject(p.xyz, int(normalAt(q).w));
    vec4 now = u_unjitteredClipFromLocal * vec4(p.xyz, 1.0);
    vec2 uvNow = now.xy / now.w * 0.5 + 0.5;
    vec2 uvBefore = r.pixel / vec2(textureSize(u_prevHistory, 0));
    return vec3(uvNow - uvBefore, 1.0 / max(length(p.xyz - u_lsEye), 1e-30));
}

// taa.wgsl:51-63 on a grey colour: YCoCg of (c, c, c) is (c, 0, 0), so the clip is Y's alone.
float clipTowardsAabbCenter(float history, float lo, float hi) {
    float p = 0.5 * (hi + lo), e = 0.5 * (hi - lo) + 0.00000001, v = history - p;
    float m = abs(v / e);
    return m > 1.0 ? p + v / m : history;
}

vec2 sampleHistory(vec2 uv) {
    SO_TAP(4, HISTORY_TEXEL_BYTES);
    return texture(u_prevHistoryLinear, uv).rg;
}

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec2 size = vec2(textureSize(u_visibility, 0)), texel = 1.0 / size;
    vec2 uv = gl_FragCoord.xy * texel;
    vec2 current = litAt(ij);  // taa.wgsl:83, the nearest tap
    float confidence = 1.0 / MIN_HISTORY_BLEND_RATE;  // a reset frame's (taa.wgsl:192-194)
    if (u_haveHistory != 0) {
        // The closest of 5 motion vectors, the diagonals 2 texels away (taa.wgsl:92-118).
        vec3 closest = motionAt(ij);
        for (int k = 0; k < 4; ++k) {
            vec3 m = motionAt(ij + 2 * ivec2((k & 1) != 0 ? 1 : -1, (k & 2) != 0 ? 1 : -1));
            if (m.z > closest.z) closest = m;
        }
        vec2 historyUv = uv - closest.xy;  // taa.wgsl:125
        // 5-tap Catmull-Rom, the corners skipped (taa.wgsl:126-141).
        vec2 samplePosition = historyUv * size;
        vec2 texelCenter = floor(samplePosition - 0.5) + 0.5;
        vec2 f = samplePosition - texelCenter;
        vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
        vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
        vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
        vec2 w3 = f * f * (-0.5 + 0.5 * f);
        vec2 w12 = w1 + w2;
        vec2 p0 = (texelCenter - 1.0) * texel, p3 = (texelCenter + 2.0) * texel,
             p12 = (texelCenter + w2 / w12) * texel;
        vec2 history = sampleHistory(vec2(p12.x, p0.y)) * w12.x * w0.y +
                       sampleHistory(vec2(p0.x, p12.y)) * w0.x * w12.y +
                       sampleHistory(p12) * w12.x * w12.y +
                       sampleHistory(vec2(p3.x, p12.y)) * w3.x * w12.y +
                       sampleHistory(vec2(p12.x, p3.y)) * w12.x * w3.y;
        // 3 x 3 variance clipping, mean +- 1 sigma (taa.wgsl:146-162), then YCoCg_to_RGB's
        // saturate (taa.wgsl:48).
        vec2 m1 = vec2(0.0), m2 = vec2(0.0);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                vec2 s = (dx == 0 && dy == 0) ? current : litAt(ij + ivec2(dx, dy));
                m1 += s;
                m2 += s * s;
            }
        vec2 mean = m1 / 9.0, sigma = sqrt(max(m2 / 9.0 - mean * mean, vec2(0.0)));
        for (int c = 0; c < 2; ++c)
            history[c] = clamp(clipTowardsAabbCenter(history[c], mean[c] - sigma[c],
                                                     mean[c] + sigma[c]), 0.0, 1.0);
        // Confidence, at the pixel itself (taa.wgsl:165-173).
        SO_TAP(1, HISTORY_TEXEL_BYTES);
        confidence = texelFetch(u_prevHistory, ij, 0).a;
        vec2 pixelMotion = abs(closest.xy) * size;
        confidence = (pixelMotion.x < 0.01 && pixelMotion.y < 0.01) ? confidence + 10.0 : 1.0;
        float factor = clamp(1.0 / confidence, MIN_HISTORY_BLEND_RATE, DEFAULT_HISTORY_BLEND_RATE);
        if (any(notEqual(clamp(historyUv, 0.0, 1.0), historyUv))) {  // taa.wgsl:180-184
            factor = 1.0;
            confidence = 1.0;
        }
        current = mix(history, current, factor);  // taa.wgsl:186
    }
    o_history = vec4(current, confidence, 0.0);  // taa.wgsl:195
    // V from the resolved images; where the surface faces away (E 0) or nothing is there, this
    // frame's V as it fell.
    o_visibility = current.y > 1e-6 ? clamp(current.x / current.y, 0.0, 1.0) : visibilityAt(ij);
}
