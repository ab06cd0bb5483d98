// lightmap (lightmap.cpp): the atlas read at a point's coordinates in texels (texel (i, j) covers
// [i, i + 1) x [j, j + 1), its centre at + 0.5), filtered here from texelFetch (no driver-defined
// filtering). Defines: FILTER_NEAREST (the texel holding the point), FILTER_BILINEAR (the four
// nearest centres), FILTER_BICUBIC (the uniform cubic B-spline over the 4 x 4 nearest: smooth,
// weights >= 0, so no ringing, but wider than bilinear).
// Each fetch is a tap of the work counts (SO_TAP): one R8 texel, one byte.
float atlasTexel(ivec2 ij) {
    SO_TAP(1, 1);
    return texelFetch(u_atlas, clamp(ij, ivec2(0), textureSize(u_atlas, 0) - 1), 0).r;
}

#ifdef FILTER_BICUBIC
vec4 bsplineWeights(float f) {
    float g = 1.0 - f;
    return vec4(g * g * g, 4.0 - 6.0 * f * f + 3.0 * f * f * f, 4.0 - 6.0 * g * g + 3.0 * g * g * g,
                f * f * f) / 6.0;
}
#endif

float lightmapLookup(vec2 texel) {
#if defined(FILTER_NEAREST)
    return atlasTexel(ivec2(floor(texel)));
#else
    vec2 s = texel - 0.5;
    ivec2 i = ivec2(floor(s));
    vec2 f = s - floor(s);
#if defined(FILTER_BILINEAR)
    return mix(mix(atlasTexel(i), atlasTexel(i + ivec2(1, 0)), f.x),
               mix(atlasTexel(i + ivec2(0, 1)), atlasTexel(i + ivec2(1, 1)), f.x), f.y);
#else
    vec4 wx = bsplineWeights(f.x), wy = bsplineWeights(f.y);
    float v = 0.0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) v += wx[x] * wy[y] * atlasTexel(i + ivec2(x - 1, y - 1));
    return v;
#endif
#endif
}
