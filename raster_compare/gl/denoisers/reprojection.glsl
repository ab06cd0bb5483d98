// The temporal passes' history (temporal.glsl, ffx.glsl): frame f - 1's accumulation, found
// through the previous camera where the point lies on the same surface (RayFrame::bindHistory
// sets the uniforms).
uniform sampler2D u_prevHistory;   // RGBA: V, first moment, second moment, history length
uniform sampler2D u_prevPosition;  // the previous frame's local positions (its frame)
uniform mat4 u_prevClipFromLocal;
uniform float u_prevScale;  // previous local = local * u_prevScale + u_prevOffset
uniform vec3 u_prevOffset;
uniform int u_haveHistory;

// The previous frame's history at the point, bilinear over the texels that saw the same surface
// (within one pixel footprint of its tangent plane, four along it); w 0 where none did.
vec4 reprojected(vec3 lsP, vec3 n) {
    vec3 prevLs = lsP * u_prevScale + u_prevOffset;
    float footprint = footprintAt(lsP) * u_prevScale;
    vec4 clip = u_prevClipFromLocal * vec4(prevLs, 1.0);
    if (clip.w <= 0.0) return vec4(0.0);
    ivec2 size = textureSize(u_prevHistory, 0);
    vec2 px = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(px));
    vec2 f = px - vec2(base);
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1), q = base + o;
        if (!inside(q, size)) continue;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        SO_TAP(1, POSITION_TEXEL_BYTES);
        vec4 pp = texelFetch(u_prevPosition, q, 0);
        vec3 d = pp.xyz - prevLs;
        if (pp.w == 0.0 || w <= 0.0 || abs(dot(d, n)) > footprint || length(d) > 4.0 * footprint)
            continue;
        SO_TAP(1, ACCUM_TEXEL_BYTES);
        sum += w * texelFetch(u_prevHistory, q, 0);
        wsum += w;
    }
    return wsum > 1e-3 ? vec4(sum.xyz / wsum, sum.w / wsum) : vec4(0.0);
}
