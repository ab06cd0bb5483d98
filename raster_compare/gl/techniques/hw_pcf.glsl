// hw-pcf (hw_pcf.cpp): the sampler's compare at the depth its bias gives.
float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    return hardwareTap(m, biasedDepth(biasState(r, m), r, m, vec2(0.0), m.d));
}
