// svgf (svgf.cpp): V and its variance for the a-trous levels (atrous.glsl), after the temporal
// pass (temporal.glsl): the variance from the temporal moments, or over 7 x 7 neighbours while
// the history is young.
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
