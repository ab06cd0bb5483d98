// One a-trous level (atrous.cpp) over V and its variance, step u_step, with SVGF's edge stops and
// its 5 x 5 B3-spline kernel.
uniform sampler2D u_filter;  // RG: V and its variance
uniform int u_step;
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
    const int R = 2;
    const float h[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
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
