// resolve=history (resolves/history.cpp): each light's V resolved through a per-light history of
// V, time/shadow_history.h's ShadowHistory on the GPU, step for step: the point's position in the
// frame before through its mesh's exact motion; its history where the pixel it falls in saw the
// same mesh within a footprint tolerance, bilinear over the texels that did; clamped to the 3 x 3
// range of this frame's V (HISTORY_CLAMP); blended with weight HISTORY_WEIGHT.
const float kSlackFootprints = 0.5;  // shadow_history.cpp's kSlackFootprints
const float kObliqueFootprints = 4.0;
const float kPositionRounding = 1e-6;

bool sameSurface(ivec2 q, int mesh, vec3 prevLs, vec2 pixel, float footprint) {
    if (!inside(q, textureSize(u_prevPosition, 0))) return false;
    SO_TAP(1, POSITION_TEXEL_BYTES);
    vec4 pp = texelFetch(u_prevPosition, q, 0);
    if (pp.w == 0.0 || int(pp.w) - 1 != mesh) return false;
    float pixels = length(vec2(q) + 0.5 - pixel);
    float tolerance = footprint * (kSlackFootprints + kObliqueFootprints * pixels) +
                      kPositionRounding * length(prevLs);
    return length(pp.xyz - prevLs) <= tolerance;
}

// The frame before's resolved V at the point; < 0 where it has none (off screen, hidden).
float historyAt(vec3 lsP, int mesh) {
    Reprojected r = reproject(lsP, mesh);
    ivec2 size = textureSize(u_prevHistory, 0);
    if (!r.inFront || !(r.pixel.x >= 0.0 && r.pixel.x < float(size.x) && r.pixel.y >= 0.0 &&
                        r.pixel.y < float(size.y)))
        return -1.0;
    float footprint = prevFootprint(r.prevLs);
    if (!sameSurface(ivec2(floor(r.pixel)), mesh, r.prevLs, r.pixel, footprint)) return -1.0;
    vec2 f = r.pixel - 0.5;
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    float sum = 0.0, wsum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1), q = base + o;
        float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
        if (!inside(q, size) || w <= 0.0 || !sameSurface(q, mesh, r.prevLs, r.pixel, footprint))
            continue;
        SO_TAP(1, HISTORY_TEXEL_BYTES);
        sum += w * texelFetch(u_prevHistory, q, 0).r;
        wsum += w;
    }
    return sum / wsum;  // the pixel it falls in has a weight of at least 1/4, and matched
}

void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec4 pos = positionAt(ij);
    float v = visibilityAt(ij);
    float resolved = v;
    if (pos.w != 0.0 && u_haveHistory != 0) {
        int mesh = int(normalAt(ij).w);
        float history = historyAt(pos.xyz, mesh);
        if (history >= 0.0) {
#ifdef HISTORY_CLAMP
            float lo = v, hi = v;
            ivec2 size = textureSize(u_visibility, 0);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    ivec2 q = ij + ivec2(dx, dy);
                    if (!inside(q, size) || positionAt(q).w == 0.0) continue;
                    float vq = visibilityAt(q);
                    lo = min(lo, vq);
                    hi = max(hi, vq);
                }
            history = clamp(history, lo, hi);
#endif
            resolved = HISTORY_WEIGHT * history + (1.0 - HISTORY_WEIGHT) * v;
        }
    }
    o_history = vec4(resolved, 0.0, 0.0, 0.0);
    o_visibility = resolved;
}
