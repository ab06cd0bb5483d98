// esm (esm.cpp): moment exp(c t); lit fraction clamp(exp(-c t) E[exp(c t)], 0, 1).
#ifdef MOMENTS_PASS
vec4 momentsOf(float t) { return vec4(exp(ESM_C * t), 0.0, 0.0, 0.0); }
#else
float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    float d = biasedDepth(biasState(r, m), r, m, vec2(0.0), m.d);  // the bias (biases/)
    return clamp(exp(-ESM_C * normalisedDepth(d)) * momentsAt(m).x, 0.0, 1.0);
}
#endif
