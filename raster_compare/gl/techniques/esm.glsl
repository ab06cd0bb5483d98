// esm (esm.cpp): moment exp(c t); lit fraction clamp(exp(-c t) E[exp(c t)], 0, 1).
#ifdef MOMENTS_PASS
vec4 momentsOf(float t) { return vec4(exp(ESM_C * t), 0.0, 0.0, 0.0); }
#else
float techniqueVisibility(Receiver r) {
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    return clamp(exp(-ESM_C * normalisedDepth(m.d)) * momentsAt(m).x, 0.0, 1.0);
}
#endif
