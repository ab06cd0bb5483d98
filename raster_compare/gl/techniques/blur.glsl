// blur (blur.cpp): one direction of the separable screen-space Gaussian (sigma = radius / 2) over
// the hit pixels; with BILATERAL, only taps whose camera-facing normal is within about 25 degrees
// and whose distance to the eye within 5% of the centre pixel's. Every fetch is a tap of the work
// counts (SO_TAP), with the targets' bytes defined by blur.cpp.
uniform sampler2D u_source;
uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform ivec2 u_step;
uniform int u_radius;
uniform vec3 u_lsEye;
layout(location = 0) out float o_value;
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    SO_TAP(1, POSITION_TEXEL_BYTES);
    vec4 p0 = texelFetch(u_position, ij, 0);
    if (p0.w == 0.0) {
        SO_TAP(1, VISIBILITY_TEXEL_BYTES);
        o_value = texelFetch(u_source, ij, 0).r;
        return;
    }
    SO_TAP(1, NORMAL_TEXEL_BYTES);
    vec3 n0 = texelFetch(u_normal, ij, 0).xyz;
    float d0 = length(p0.xyz - u_lsEye);
    float sigma = max(0.5 * float(u_radius), 0.5);
    ivec2 size = textureSize(u_source, 0);
    float sum = 0.0, wsum = 0.0;
    for (int i = -u_radius; i <= u_radius; ++i) {
        ivec2 q = ij + i * u_step;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        SO_TAP(1, POSITION_TEXEL_BYTES);
        vec4 p = texelFetch(u_position, q, 0);
        if (p.w == 0.0) continue;  // background carries no shadow
#ifdef BILATERAL
        SO_TAP(1, NORMAL_TEXEL_BYTES);
        if (dot(texelFetch(u_normal, q, 0).xyz, n0) < 0.9) continue;
        if (abs(length(p.xyz - u_lsEye) - d0) > 0.05 * d0) continue;
#endif
        float w = exp(-0.5 * float(i * i) / (sigma * sigma));
        SO_TAP(1, VISIBILITY_TEXEL_BYTES);
        sum += w * texelFetch(u_source, q, 0).r;
        wsum += w;
    }
    if (wsum > 0.0) {
        o_value = sum / wsum;
        return;
    }
    SO_TAP(1, VISIBILITY_TEXEL_BYTES);
    o_value = texelFetch(u_source, ij, 0).r;
}
