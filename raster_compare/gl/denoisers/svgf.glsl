// svgf (svgf.cpp): V and its variance for the a-trous levels (atrous.glsl), after the temporal
// pass (temporal.glsl): the variance from the temporal moments, or V and the variance filtered over
// 7 x 7 neighbours while the history is young.
uniform sampler2D u_accum;
uniform float u_sigmaNormal, u_sigmaLuminance, u_sigmaDepth;
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
    // SVGF 4.2 as Falcor's SVGFFilterMoments.ps.slang (51-123) writes it: too young a history
    // for temporal moments, V and its moments cross-bilaterally filtered over 7 x 7 neighbours
    // (kernel 1; Falcor's computeWeight, SVGFCommon.slang: the normal stop, the depth stop at 3
    // depth gradients a pixel of distance, V's stop `sigma_luminance` unscaled by the variance),
    // the variance from those moments boosted by 4 / length.
    vec3 n = normalAt(ij);
    float footprint = footprintAt(pos.xyz);
    ivec2 size = textureSize(u_accum, 0);
    vec3 sum = vec3(0.0);  // V, first and second moments
    float wsum = 0.0;
    for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
            ivec2 q = ij + ivec2(dx, dy);
            if (!inside(q, size)) continue;
            vec4 pq = positionAt(q);
            if (pq.w == 0.0) continue;  // Falcor's depth stop leaves the sky next to nothing
            SO_TAP(1, ACCUM_TEXEL_BYTES);
            vec3 a = texelFetch(u_accum, q, 0).xyz;
            float wz = dx == 0 && dy == 0
                           ? 0.0
                           : abs(dot(n, pq.xyz - pos.xyz)) /
                                 (u_sigmaDepth * 3.0 * footprint * length(vec2(dx, dy)));
            float w = pow(clamp(dot(n, normalAt(q)), 0.0, 1.0), u_sigmaNormal) *
                      exp(-abs(acc.x - a.x) / u_sigmaLuminance - wz);
            sum += w * a;
            wsum += w;
        }
    sum /= max(wsum, 1e-6);
    o_filter = vec2(sum.x, (sum.z - sum.y * sum.y) * 4.0 / acc.w);
}
