// hitdist (hitdist.cpp): the temporal history (temporal.glsl) filtered over a disk as wide as
// the penumbra; SEARCH_RADIUS and PENUMBRA_TAPS defined.
uniform sampler2D u_accum;  // x: V accumulated over time
uniform sampler2D u_raw;    // y: this frame's mean blocker distance (0: no ray was blocked)
uniform float u_lsLightSize;
uniform vec3 u_lsLightCenter;
uniform float u_maxRadius;
uniform float u_radiusScale;
uniform float u_sigmaNormal;
layout(location = 0) out vec2 o_filter;
// The penumbra's size from the blocker distance by similar triangles (PCSS's estimate), w = light
// size x d_blocker / (d_light - d_blocker), sets the filter's radius. The blocker distance is the mean of the blocked rays' distances over the
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
