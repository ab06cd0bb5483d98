// smrt (smrt.cpp) on the plain map (map=plain), after shaders/shadow_map.frag and
// techniques/smrt_rays.glsl: each sample of a ray is looked up in the one depth map.
HeightSample heightSample(vec3 q) {
    HeightSample s;
    MapPoint m = mapPoint(q);
    s.covered = !m.outside;
    if (!s.covered) return s;
    s.d = m.d;
    s.texel = texelWorld(m.d);
    s.stored = storedDepthAt(m, vec2(0.0));
    return s;
}

float mapDepth(vec3 q) { return receiverDepth(q); }

float techniqueVisibility(Receiver r) {
    if (mapPoint(r.p).outside) return 1.0;
    return smrtVisibility(r.p, slopeBias(r, SLOPE_FACTOR, SLOPE_MIN, SLOPE_MAX, 1.0), r.texel);
}
