// msm (msm.cpp): moments (t, t^2, t^3, t^4); Hamburger 4MSM (Peters and Klein 2015, algorithm 2).
#ifdef MOMENTS_PASS
vec4 momentsOf(float t) {
    float t2 = t * t;
    return vec4(t, t2, t2 * t, t2 * t2);
}
#else
// The lit fraction for a receiver at normalised depth z, from the filtered moments.
float hamburger4(vec4 moments, float z) {
    vec4 b = mix(moments, vec4(0.5), MOMENT_BIAS);
    // Cholesky factorisation of the Hankel matrix, non-trivial entries only.
    float L32D22 = -b.x * b.y + b.z;
    float D22 = -b.x * b.x + b.y;
    float squaredDepthVariance = -b.y * b.y + b.w;
    float D33D22 = dot(vec2(squaredDepthVariance, -L32D22), vec2(D22, L32D22));
    float InvD22 = 1.0 / D22;
    float L32 = L32D22 * InvD22;
    // Solve B c = (1, z, z^2) by forward substitution, scaling and back substitution.
    vec3 c = vec3(1.0, z, z * z);
    c.y -= b.x;
    c.z -= b.y + L32 * c.y;
    c.y *= InvD22;
    c.z *= D22 / D33D22;
    c.y -= L32 * c.z;
    c.x -= dot(c.yz, b.xy);
    // The roots z1 <= z2 of c.x + c.y x + c.z x^2: the other two support points.
    float p = c.y / c.z;
    float q = c.x / c.z;
    float r = sqrt(max(p * p * 0.25 - q, 0.0));
    float z1 = -p * 0.5 - r;
    float z2 = -p * 0.5 + r;
    vec4 s = z2 < z ? vec4(z1, z, 1.0, 1.0) : (z1 < z ? vec4(z, z1, 0.0, 1.0) : vec4(0.0));
    float quotient = (s.x * z2 - b.x * (s.x + z2) + b.y) / ((z2 - s.y) * (z - z1));
    float shadow = s.z + s.w * quotient;
    return 1.0 - clamp(shadow, 0.0, 1.0);
}
float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    float d = biasedDepth(biasState(r, m), r, m, vec2(0.0), m.d);  // the bias (biases/)
    return reduceBleeding(hamburger4(momentsAt(m), normalisedDepth(d)), BLEED_REDUCTION);
}
#endif
