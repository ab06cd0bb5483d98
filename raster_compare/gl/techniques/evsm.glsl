// evsm (evsm.cpp): moments of the positive and negative warps; the smaller Chebyshev bound.
#ifdef MOMENTS_PASS
vec4 momentsOf(float t) {
    float p = exp(EVSM_CPOS * t), n = -exp(-EVSM_CNEG * t);
    return vec4(p, p * p, n, n * n);
}
#else
float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    float d = biasedDepth(biasState(r, m), r, m, vec2(0.0), m.d);  // the bias (biases/)
    vec4 moments = momentsAt(m);
    float t = normalisedDepth(d);
    float p = exp(EVSM_CPOS * t), n = -exp(-EVSM_CNEG * t);
    float vp = chebyshev(moments.xy, p, MIN_VARIANCE * EVSM_CPOS * EVSM_CPOS * p * p);
    float vn = chebyshev(moments.zw, n, MIN_VARIANCE * EVSM_CNEG * EVSM_CNEG * n * n);
    return reduceBleeding(min(vp, vn), BLEED_REDUCTION);
}
#endif
