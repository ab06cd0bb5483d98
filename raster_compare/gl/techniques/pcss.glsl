// pcss (pcss.cpp): blocker search, penumbra width by similar triangles, variable PCF. Offsets are
// in texels at the receiver (angles, for perspective and cube maps).
uniform float u_lightSize;  // local units; directional: tan of the angular size

// Point k of n on a golden-angle spiral filling the unit disk; with PATTERN_ROTATED the spiral is
// turned per pixel by interleaved gradient noise (Jimenez 2014), fixed per pixel (deterministic).
vec2 spiral(int k, int n) {
    float r = sqrt((float(k) + 0.5) / float(n));
    float a = float(k) * 2.39996323;
#ifdef PATTERN_ROTATED
    a += 6.28318531 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
#endif
    return r * vec2(cos(a), sin(a));
}

// The texels the light's width spans at the receiver's depth dR, seen through a point at depth d
// (similar triangles: width * (dR - d) / d in world units at d, then into texels there).
float texelsThrough(Receiver r, float dR, float d) {
#ifdef LIGHT_ORTHO
    return 0.5 * u_lightSize * (dR - d) / r.texel;
#else
    return 0.5 * u_lightSize * (dR - d) / (d * dR * u_texelScale);
#endif
}

float techniqueVisibility(Receiver r) {
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    float dR = m.d;
    // The texels one light-size-wide cone through the receiver spans at depth d: the search
    // covers blockers down to the near plane, the penumbra those at the blockers' depth.
    float searchTexels = min(texelsThrough(r, dR, u_near), SEARCH_MAX);
    float dRefSearch = dR - slopeBias(r, SLOPE_ALPHA, SLOPE_MIN, SLOPE_MAX, 1.0 + searchTexels);
    float blockerSum = 0.0;
    int blockers = 0;
    for (int k = 0; k < BLOCKER_SAMPLES; ++k) {
        float d = storedDepthAt(m, spiral(k, BLOCKER_SAMPLES) * searchTexels);
        if (d < dRefSearch) {
            blockerSum += d;
            ++blockers;
        }
    }
    if (blockers == 0) return 1.0;
    float dB = blockerSum / float(blockers);
    float filterTexels = min(texelsThrough(r, dR, dB), FILTER_MAX);
    float dRef = dR - slopeBias(r, SLOPE_ALPHA, SLOPE_MIN, SLOPE_MAX, 1.0 + filterTexels);
    if (filterTexels < 0.5) return depthTapAt(m, vec2(0.0), dRef);
    float lit = 0.0;
    for (int k = 0; k < FILTER_SAMPLES; ++k)
        lit += depthTapAt(m, spiral(k, FILTER_SAMPLES) * filterTexels, dRef);
    return lit / float(FILTER_SAMPLES);
}
