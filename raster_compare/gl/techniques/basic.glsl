// basic (basic.cpp), and the bias techniques it expands to (slope-bias = basic:bias=slope, ...):
// one depth compare at the receiver's own texel, at the depth its bias (biases/) gives.
float techniqueVisibility(Receiver r) {
    r.p = biasedPoint(r);
    MapPoint m = mapPoint(r.p);
    if (m.outside) return 1.0;
    return depthTap(m, ivec2(0), biasedDepth(biasState(r, m), r, m, vec2(0.0), m.d));
}
