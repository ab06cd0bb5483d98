// pcss (pcss.cpp): blocker search, penumbra width by similar triangles, variable PCF. Offsets are
// in texels at the receiver (angles, for perspective and cube maps).
uniform float u_lightSize;  // local units; directional: tan of the angular size

// Point k of n on a golden-angle spiral filling the unit disk; with PATTERN_ROTATED the spiral is
// turned per pixel by interleaved gradient noise (Jimenez 2014), fixed per pixel (deterministic);
// with TEMPORAL turned per pixel and per frame (shaders/taps.glsl's tapRotation).
vec2 spiral(int k, int n) {
#if defined(PATTERN_ROTATED) || defined(TEMPORAL)
    return vogelTap(k, n, tapRotation());
#else
    return vogelTap(k, n, 0.0);
#endif
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

// The depth of the receiver's plane (through r.p, normal r.n) along the map's ray o texels from
// the point's own (Isidoro's receiver-plane depth): each tap is tested against the receiver where
// that ray meets it, so the bias need not grow with the filter's width. -1 where the ray does not
// meet the plane in front of the light (beyond the receiver's horizon): the tap is left out.
float planeDepthAt(Receiver r, MapPoint m, vec2 o) {
#ifdef LIGHT_ORTHO
    // The light looks down -z; n.z = n.l > 0 for a receiver the light faces.
    vec3 n = mat3(u_lightViewFromLocal) * r.n;
    return m.d + r.texel * dot(n.xy, o) / n.z;
#else
#ifdef LIGHT_CUBE
    vec3 n = r.n, v = m.v;
    vec3 tap = v + m.step * (o.x * m.t1 + o.y * m.t2);
#else
    vec3 n = mat3(u_lightViewFromLocal) * r.n, v = (u_lightViewFromLocal * vec4(r.p, 1.0)).xyz;
    vec3 tap = v + vec3(m.d * u_texelScale * o, 0.0);
#endif
    // The plane's point along the tap's ray is s * tap from the light; its depth is measured along
    // the axis of the face the tap reads (a cube's taps may cross into the next face).
    float s = dot(n, v) / dot(n, tap);
    vec3 a = abs(tap);
#ifdef LIGHT_CUBE
    float axis = max(a.x, max(a.y, a.z));
#else
    float axis = a.z;
#endif
    return s > 0.0 ? s * axis : -1.0;
#endif
}

float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    float dR = m.d;
    // Blockers are looked for, and taken, no nearer the light than dMin: the penumbra's half-width
    // at the receiver is then at most PENUMBRA_MAX light half-widths, whatever the map's texel
    // (directional lights: down to the scene's top, the near plane). Also at most the map's side.
#ifdef LIGHT_ORTHO
    float dMin = u_near;
#else
    float dMin = max(u_near, dR / (1.0 + PENUMBRA_MAX));
#endif
    float mapSide = float(MAP_SIZE.x);
    float searchTexels = min(texelsThrough(r, dR, dMin), mapSide);
    // Each tap at the receiver's plane along the tap's ray, less its bias (biases/; by default the
    // slope bias of one texel: the texel's own footprint on the slope; the plane does the rest).
    BiasState b = biasState(r, m);
    float blockerSum = 0.0;
    int blockers = 0;
    for (int k = 0; k < BLOCKER_SAMPLES; ++k) {
        vec2 o = spiral(k, BLOCKER_SAMPLES) * searchTexels;
        float plane = planeDepthAt(r, m, o);
        if (plane < 0.0) continue;
        float d = storedDepthAt(m, o);
        if (d < biasedDepth(b, r, m, o, plane)) {
            blockerSum += d;
            ++blockers;
        }
    }
    if (blockers == 0) return 1.0;
    float dB = max(blockerSum / float(blockers), dMin);
    float filterTexels = min(texelsThrough(r, dR, dB), mapSide);
    float own = biasedDepth(b, r, m, vec2(0.0), dR);
    if (filterTexels < 0.5) return depthTapAt(m, vec2(0.0), own);
    float lit = 0.0, taps = 0.0;
    for (int k = 0; k < FILTER_SAMPLES; ++k) {
        vec2 o = spiral(k, FILTER_SAMPLES) * filterTexels;
        float plane = planeDepthAt(r, m, o);
        if (plane < 0.0) continue;
        lit += depthTapAt(m, o, biasedDepth(b, r, m, o, plane));
        taps += 1.0;
    }
    return taps > 0.0 ? lit / taps : depthTapAt(m, vec2(0.0), own);
}
