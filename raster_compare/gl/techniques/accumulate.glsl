// accumulate (accumulate.cpp): the weight pass adds (G v, G) of one sample to the sums, per
// pixel, from the camera pass's position and normal; the resolve pass writes sum(G v) / sum(G).
// Defines: WEIGHT_PASS, and EMITTER_POINT (not an area light: one sample, whose V already holds
// the facing test, weight 1),
// EMITTER_ONE_SIDED (rect, disk), EMITTER_SPHERE. Every fetch is a tap of the work counts (SO_TAP),
// with the targets' bytes defined by accumulate.cpp.
#ifdef WEIGHT_PASS
uniform sampler2D u_visibility;
uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform vec3 u_lsSample;
uniform vec3 u_lsLightCenter;
uniform vec3 u_lsEmitNormal;
layout(location = 0) out vec2 o_sums;
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    SO_TAP(1, POSITION_TEXEL_BYTES);
    vec4 pos = texelFetch(u_position, ij, 0);
    if (pos.w == 0.0) discard;
    SO_TAP(1, NORMAL_TEXEL_BYTES);
    vec3 n = normalize(texelFetch(u_normal, ij, 0).xyz);
    vec3 d = u_lsSample - pos.xyz;
    float r2 = dot(d, d);
    vec3 l = d * inversesqrt(r2);
    float cosR = dot(n, l);
#ifdef EMITTER_POINT
    float g = 1.0;
#else
#ifdef EMITTER_SPHERE
    vec3 ny = normalize(u_lsSample - u_lsLightCenter);
#else
    vec3 ny = u_lsEmitNormal;
#endif
    float cosE = dot(ny, -l);
    float g = (cosR > 0.0 && cosE > 0.0) ? cosR * cosE / r2 : 0.0;
#endif
    SO_TAP(1, VISIBILITY_TEXEL_BYTES);
    o_sums = vec2(g * texelFetch(u_visibility, ij, 0).r, g);
}
#else
uniform sampler2D u_sums;
layout(location = 0) out float o_visibility;
layout(location = 1) out float o_aliasing;
void main() {
    SO_TAP(1, SUMS_TEXEL_BYTES);
    vec2 s = texelFetch(u_sums, ivec2(gl_FragCoord.xy), 0).rg;
    o_visibility = s.y > 0.0 ? s.x / s.y : 0.0;
    o_aliasing = 0.0;
}
#endif
