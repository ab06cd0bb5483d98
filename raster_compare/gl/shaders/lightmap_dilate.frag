// The lightmap's bake after its samples (lightmap_bake.h): full-screen passes over the atlas.
//   RESOLVE: (V, filled) per texel: V = sum(G v) / sum(G) from the weight passes' sums (0 where
//            G was 0 for every sample), filled where a triangle covers the texel's centre;
//   DILATE:  an empty texel with filled ones among its 4 edge neighbours takes their mean and
//            becomes filled: the charts grow one texel per pass into their padding (llvmpipe has
//            no conservative rasterisation, so a texel a triangle only partly covers is empty).
//            Along a straight chart edge that copies the edge texel outwards, as clamping to the
//            edge would; the diagonal neighbours are left out because they would carry a shadow
//            edge that meets the chart's border half a texel along it (a corner fills on the
//            next pass);
//   FILLED:  discards the empty texels (a GL_SAMPLES_PASSED query counts the others);
//   STORE:   V into the atlas (GL_R8); what is still empty stores 0.
uniform sampler2D u_source;    // RESOLVE: the sums (G v, G); others: (V, filled)
uniform sampler2D u_geometry;  // RESOLVE: the texels' points, w = 1 where covered
#if defined(STORE)
layout(location = 0) out float o_visibility;
#else
layout(location = 0) out vec2 o_value;
#endif
void main() {
    ivec2 ij = ivec2(gl_FragCoord.xy);
    vec2 s = texelFetch(u_source, ij, 0).rg;
#if defined(RESOLVE)
    float filled = texelFetch(u_geometry, ij, 0).w;
    o_value = vec2(s.y > 0.0 ? s.x / s.y : 0.0, filled);
#elif defined(DILATE)
    o_value = s;
    if (s.y != 0.0) return;
    ivec2 size = textureSize(u_source, 0);
    const ivec2 steps[4] = ivec2[](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    float sum = 0.0, n = 0.0;
    for (int d = 0; d < 4; ++d) {
        ivec2 k = ij + steps[d];
        if (any(lessThan(k, ivec2(0))) || any(greaterThanEqual(k, size))) continue;
        vec2 t = texelFetch(u_source, k, 0).rg;
        if (t.y != 0.0) {
            sum += t.x;
            n += 1.0;
        }
    }
    if (n > 0.0) o_value = vec2(sum / n, 1.0);
#elif defined(FILLED)
    if (s.y == 0.0) discard;
    o_value = s;
#else
    o_visibility = s.x;
#endif
}
