// vsm (vsm.cpp): moments (t, t^2); the Chebyshev bound with the bleeding reduction.
#ifdef MOMENTS_PASS
vec4 momentsOf(float t) { return vec4(t, t * t, 0.0, 0.0); }
#else
float techniqueVisibility(Receiver r) {
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    return reduceBleeding(chebyshev(momentsAt(m).xy, normalisedDepth(m.d), MIN_VARIANCE), BLEED_REDUCTION);
}
#endif
