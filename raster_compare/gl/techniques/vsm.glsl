// vsm (vsm.cpp): moments (t, t^2); the Chebyshev bound with the bleeding reduction.
#ifdef MOMENTS_PASS
vec4 momentsOf(float t) { return vec4(t, t * t, 0.0, 0.0); }
#else
float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    float d = biasedDepth(biasState(r, m), r, m, vec2(0.0), m.d);  // the bias (biases/)
    return reduceBleeding(chebyshev(momentsAt(m).xy, normalisedDepth(d), MIN_VARIANCE), BLEED_REDUCTION);
}
#endif
