// The temporal passes' history (temporal.glsl; ffx.glsl reads the same uniforms): frame f - 1's
// accumulation, found through the previous camera where the point lies on the same surface
// (RayFrame::bindHistory sets the uniforms). Falcor's SVGFReproject.ps.slang (NVIDIAGameWorks/
// Falcor eb540f67, Source/RenderPasses/SVGFPass: loadPrevData, 80-184) step for step, with the
// same-surface test below for its depth and normal one.
uniform sampler2D u_prevHistory;   // RGBA: V, first moment, second moment, history length
uniform sampler2D u_prevPosition;  // the previous frame's local positions (its frame)
uniform mat4 u_prevClipFromLocal;
uniform float u_prevScale;  // the frame before's local unit over this frame's
uniform int u_haveHistory;

// Whether previous texel q saw the surface through prevLs (normal n): within one pixel footprint
// of its tangent plane, four along it.
bool sameSurface(ivec2 q, vec3 prevLs, vec3 n, float footprint) {
    if (!inside(q, textureSize(u_prevHistory, 0))) return false;
    SO_TAP(1, POSITION_TEXEL_BYTES);
    vec4 pp = texelFetch(u_prevPosition, q, 0);
    vec3 d = pp.xyz - prevLs;
    return pp.w != 0.0 && abs(dot(d, n)) <= footprint && length(d) <= 4.0 * footprint;
}

// The previous frame's history at the point: bilinear over the texels that saw the same surface
// (Falcor 97-139); where none of the four did, the mean of those around the nearest texel that did
// (its 3 x 3 cross-bilateral fallback, 141-169); w 0 where none did. The history length is the
// nearest texel's (Falcor 171-175).
vec4 reprojected(vec3 lsP, vec3 n) {
    mat4 prevFromLocal = previousFromLocal();
    vec3 prevLs = (prevFromLocal * vec4(lsP, 1.0)).xyz;
    n = normalize(mat3(prevFromLocal) * n);
    float footprint = footprintAt(lsP) * u_prevScale;
    vec4 clip = u_prevClipFromLocal * vec4(prevLs, 1.0);
    if (clip.w <= 0.0) return vec4(0.0);
    ivec2 size = textureSize(u_prevHistory, 0);
    vec2 px = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5;
    ivec2 base = ivec2(floor(px)), nearest = ivec2(floor(px + 0.5));
    vec2 f = px - vec2(base);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1), q = base + o;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (!sameSurface(q, prevLs, n, footprint)) continue;
        SO_TAP(1, ACCUM_TEXEL_BYTES);
        sum += w * texelFetch(u_prevHistory, q, 0).xyz;
        wsum += w;
    }
    if (wsum >= 0.01) {
        sum /= wsum;
    } else {
        sum = vec3(0.0);
        float valid = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec2 q = nearest + ivec2(dx, dy);
                if (!sameSurface(q, prevLs, n, footprint)) continue;
                SO_TAP(1, ACCUM_TEXEL_BYTES);
                sum += texelFetch(u_prevHistory, q, 0).xyz;
                valid += 1.0;
            }
        if (valid == 0.0) return vec4(0.0);
        sum /= valid;
    }
    SO_TAP(1, ACCUM_TEXEL_BYTES);
    // 0 where the nearest texel saw nothing: the new frame alone, as Falcor's max(alpha, 1 / 1).
    return vec4(sum, texelFetch(u_prevHistory, clamp(nearest, ivec2(0), size - 1), 0).w);
}
